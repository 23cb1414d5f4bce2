#pragma once
/// @file hidden_lidar.hpp  LiDAR points the camera cannot see, found by stereo and left out of
/// the fused cost.
///
/// The LiDAR sits apart from the left camera, so near an object's edge it sees past the object
/// to the background the camera sees the object in front of ("boundary bleeding"); glass returns
/// what lies behind it; a car that moved between the scan's sweep and the exposure leaves its
/// points where the camera sees road. Projected, such a point lands on a pixel whose surface is
/// nearer than the point. In the fused cost (Eq. 5) it pulls that pixel and, through the paths
/// (Eq. 1), its neighbours back to the far disparity: on KITTI stereo 2015 with the raw scans,
/// 19 % of the points on objects disagree with the GT by more than 3 px and 5 %, against 1 % of
/// the background's.
///
/// The stereo pair is the witness: a stereo-only SGM (Eq. 1-2 on C_S alone, with the left-right
/// check, so occluded pixels have no vote) is run first, and a point is left out of the fused
/// matching where
///  1. its pixel has a stereo disparity, and the farthest stereo disparity within +-halfWidth
///     columns is NEARER than the point by more than minGap px and relativeGap of its disparity
///     (the window: stereo fattens a near object's edge over the background by a few pixels);
///  2. another LiDAR point within +-supportHalfWidth columns and +-supportHalfHeight rows lies at
///     that nearer disparity (within minGap): the LiDAR itself saw the surface in front (the
///     object it saw past, the car body around a window).
/// Only the nearer direction: where stereo sees a farther surface than the LiDAR, stereo is
/// usually the one that is wrong (textureless car bodies), and dropping both ways costs the
/// background. Without the LiDAR's own support, stereo's mistakes drop right points: on the
/// protocols whose LiDAR is exact (P1 samples the GT) every dropped point is a loss.
///
/// Measured with lidar_sgm_eval (docs/RESULTS.md, "Hidden LiDAR points"): KITTI142 fused, 29
/// frames, error total 2.73 -> 2.38 %, foreground 9.06 -> 7.03 %, correct 98.39 -> 98.67 %; P1-P3
/// fused "correct" within -0.19 points but Middlebury's (-0.42: fattened edges the LiDAR supports).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {

struct HiddenLidarOptions {
  bool enabled = true;
  /// A point is hidden where the stereo disparity exceeds its own by more than minGap px AND by
  /// more than relativeGap x its disparity (KITTI's 3 px / 5 % "wrong" rule, measured best at
  /// 2-3 px). minGap in [0.5, 64] px, relativeGap in [0, 1].
  double minGap = 3.0;
  double relativeGap = 0.05;
  /// The witness is the farthest stereo disparity within +-halfWidth columns of the point's
  /// pixel (whose own stereo disparity must exist), in [0, 16] px.
  int halfWidth = 2;
  /// Another LiDAR point within +-supportHalfWidth columns and +-supportHalfHeight rows must lie
  /// within minGap of the witness's disparity, in [0, 64] px each.
  int supportHalfWidth = 6;
  int supportHalfHeight = 4;
  /// Scale of the stereo witness relative to the frame's: 0.5 (half the frame's scale: a quarter
  /// of its pixels and half its disparities, about an eighth of the work), 0.25 (an eighth of the
  /// frame's work again) or 1 (the frame's own). Below half scale of the pair, the pair is halved
  /// first (once or twice), then matched at half scale. Measured on KITTI142: a full-scale frame's
  /// fused error total is 2.35 % at 0.5; a half-scale frame's 2.79 % at 0.5 against 2.77 % at 1.
  float witnessScale = 0.5f;
  /// The witness is matched only on the rows the points span, widened by this many rows above
  /// and below (frame pixels) for its paths to settle before they reach a point, in [0, 4096].
  int witnessMarginRows = 16;
};

/// Rows [begin, end) of an image of `height` rows that the witness is matched on: those of
/// `samples`, widened by `marginRows` each way, `begin` rounded down and `end` up to a multiple of
/// `block` (clamped to the image), so that the rows of a pair halved once or twice are those of
/// the whole pair halved. Empty (begin == end) without samples.
struct WitnessRows {
  int begin = 0;
  int end = 0;
};
WitnessRows witnessRows(const std::vector<LidarSample>& samples, int height, int marginRows, int block);

/// Throws std::invalid_argument naming the field when `options` are out of range.
void validate(const HiddenLidarOptions& options);

/// Removes from `samples` (pixel and x16 disparity in the left image) the points that
/// `stereoDisparity16` (the stereo-only disparity of the same left image, x16, kInvalidDisparity
/// where it has none) sees a nearer surface in front of; returns how many. `scan` is the frame's
/// projected scan (the same size), whose points vouch for the nearer surface. Points on pixels
/// without a stereo disparity, or outside the image, are kept.
std::size_t dropHiddenLidar(ImageView<const std::int16_t> stereoDisparity16, const LidarPoints& scan,
                            std::vector<LidarSample>& samples, const HiddenLidarOptions& options);

}  // namespace lidar_sgm
