#pragma once
// The fixed-point forms of the two real-valued settings the backends compute with. Internal to
// the core, which puts them into the frame plan (frame_plan.hpp); the backends' stage contract
// (backends/common/stages.hpp) includes it, so the arrow points from the backends to the core.

#include <cmath>

namespace lidar_sgm {

/// Eq. 5 in fixed point: alpha as an integer weight out of 256.
inline int alphaWeight(float alpha) { return static_cast<int>(alpha * 256.0f + 0.5f); }

/// Triple-SGM: the up camera's baseline over the stereo baseline, b_up / b, in fixed point
/// (x65536, rounded). A point of horizontal disparity d has vertical disparity d * ratio16 / 65536.
inline int baselineRatio16(double baselineRatio) {
  return static_cast<int>(std::lround(baselineRatio * 65536.0));
}

}  // namespace lidar_sgm
