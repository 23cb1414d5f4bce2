#pragma once
/// @file lidar_consistency.hpp  LiDAR points that the stereo pair contradicts, left out of the
/// fused cost.
///
/// A LiDAR point can be wrong for the camera while right for the LiDAR: a moving car has moved
/// between the scan's sweep and the exposure, glass returns what lies behind it, an object's
/// edge is seen past by the LiDAR from its other viewpoint. On KITTI stereo 2015's frames with
/// their raw scans, 19 % of the points on objects disagree with the GT by more than 3 px and 5 %,
/// against 1 % of the background's (the GT's moving cars are fitted at the camera's instant).
/// In the fused cost (Eq. 5) such a point pulls its pixels and, through the paths, their
/// neighbours to its wrong disparity. The pair itself is the witness: where the left patch
/// matches the right one clearly better at another disparity than at the point's, the point is
/// left out of the matching (it stays in the projected scan).
///
/// Off by default: measured with lidar_sgm_eval (docs/RESULTS.md) before the hidden-LiDAR filter
/// (hidden_lidar.hpp, on by default, which catches many of the same points), it lowered KITTI142's
/// error (fused, 29 frames: total 2.73 -> 2.50 %, foreground 9.06 -> 6.63 %, correct 98.39 -> 98.50 %)
/// but costs 0.2-0.4 points of "correct" on P1, P2 and P3, whose LiDAR is exact or whose GT is
/// LiDAR: there every dropped point was right (often a background point the right camera cannot
/// see beside a nearer object, where the pair cannot match it at all). Exempting the points a
/// nearer LiDAR surface hides from the right camera gave back P1-P3 but also most of KITTI142's
/// gain, so it was not kept.

#include <cstddef>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {

struct LidarConsistencyOptions {
  bool enabled = false;
  /// A point is contradicted when the 7x7 zero-mean SAD at its disparity (the best of d - 1, d,
  /// d + 1) exceeds costRatio x the best SAD within +-searchRadius px plus marginPerPixel x 49, the
  /// best lies more than minDisagreement px away, and the left patch has texture. Measured on 8
  /// KITTI142 frames: 1.5 leaves out about 65 % of the wrong points on objects and 3-5 % of the
  /// right ones. In [1, 100].
  double costRatio = 1.5;
  double marginPerPixel = 2.0;   ///< gray levels per pixel (8 bit; x257 for 16-bit images), in [0, 255]
  int searchRadius = 32;         ///< px around the point's disparity, in [4, 256]
  double minDisagreement = 3.0;  ///< px, in [1, 64]
};

/// Throws std::invalid_argument naming the field when `options` are out of range.
void validate(const LidarConsistencyOptions& options);

/// Removes from `samples` (pixel and x16 disparity in the left image) the points the pair
/// `left`/`right` (same size and depth) contradicts; returns how many. Points whose patches
/// leave the images, and textureless ones, are kept.
std::size_t dropInconsistentLidar(const GrayImageView& left, const GrayImageView& right,
                                  std::vector<LidarSample>& samples, const LidarConsistencyOptions& options);

}  // namespace lidar_sgm
