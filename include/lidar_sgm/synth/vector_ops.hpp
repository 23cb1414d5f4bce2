#pragma once
/// @file vector_ops.hpp  dot, norm, normalized for the ray tracer's Eigen::Vector3d, in a fixed
/// arithmetic order.
///
/// Why not Eigen's a.dot(b), norm(), normalized(): Eigen's summation order depends on the build
/// (its scalar unrolled reduction adds x + (y + z), its SSE path (x + y) + z), and normalized()
/// divides by the norm, where the generator has always computed (x + y) + z and multiplied by
/// 1 / norm. Rendered frames and data/sample must be bit-identical on every build, so the order
/// is written out here.

#include <cmath>

#include <Eigen/Core>

namespace lidar_sgm {
namespace synth {

inline double dot(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}
inline double norm(const Eigen::Vector3d& a) { return std::sqrt(dot(a, a)); }
inline Eigen::Vector3d normalized(const Eigen::Vector3d& a) { return a * (1.0 / norm(a)); }

}  // namespace synth
}  // namespace lidar_sgm
