#pragma once
/// @file disparity.hpp  Depth <-> disparity for a rectified pair (Eq. 3).

#include <cmath>

namespace lidar_sgm {
namespace geometry {

/// d = f*b/z (Eq. 3); `focalBaseline` = focal length [px] * baseline [m]. NaN unless z > 0 and finite.
inline double disparityFromDepth(double focalBaseline, double depth) {
  return depth > 0.0 && std::isfinite(depth) ? focalBaseline / depth : std::nan("");
}

/// z = f*b/d; NaN unless d > 0 and finite.
inline double depthFromDisparity(double focalBaseline, double disparity) {
  return disparity > 0.0 && std::isfinite(disparity) ? focalBaseline / disparity : std::nan("");
}

}  // namespace geometry
}  // namespace lidar_sgm
