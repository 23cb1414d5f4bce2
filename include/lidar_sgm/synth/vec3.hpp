#pragma once
/// @file vec3.hpp  The few 3D vector operations the ray tracer needs (no Eigen in lidar_sgm::synth).

#include <cmath>

namespace lidar_sgm {
namespace synth {

struct Vec3 {
  double x = 0;
  double y = 0;
  double z = 0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(double s, const Vec3& a) { return a * s; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(const Vec3& a) { return a * (1.0 / norm(a)); }

/// Linear RGB in [0, 1] per channel (before the camera's 8-bit quantisation).
struct Rgb {
  double r = 0;
  double g = 0;
  double b = 0;
};

inline Rgb operator+(const Rgb& a, const Rgb& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline Rgb operator*(const Rgb& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
inline Rgb operator*(const Rgb& a, const Rgb& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline Rgb mix(const Rgb& a, const Rgb& b, double t) { return a * (1.0 - t) + b * t; }

}  // namespace synth
}  // namespace lidar_sgm
