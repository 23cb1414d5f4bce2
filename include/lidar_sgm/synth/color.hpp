#pragma once
/// @file color.hpp  Linear RGB for shading (the 8-bit camera output is the core's lidar_sgm::Rgb8).

namespace lidar_sgm {
namespace synth {

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
