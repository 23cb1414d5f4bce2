#pragma once
/// @file lidar_anchor.hpp  The LiDAR's sub-pixel disparity carried onto the matched surface, where
/// the scene is far.
///
/// SGM's sub-pixel disparity comes from a parabola through three integer costs (Eq. 2's winner
/// and its neighbours), which locks towards whole pixels and is noisy on weak texture. Near, that
/// is a few centimetres; far, it is the error: at KITTI's f*b = 384 px*m a 0.1 px error is 0.4 m
/// at 20 m and 1.5 m at 60 m. The LiDAR measures those depths to a few centimetres, so where a
/// LiDAR point agrees with the matched surface, the difference between the two at the point's
/// pixel (its residual) is the matcher's local error, and it varies slowly along a surface.
///
/// Each pixel p whose matched disparity is at most maxDisparity (the far scene) takes the
/// Gaussian-weighted mean of the residuals r_q = d_LiDAR(q) - d(q) of the LiDAR points q within
/// +-halfWidth columns and +-halfHeight rows for which
///  1. |r_q| <= agreement px: the point lies on the surface the matcher found at its own pixel
///     (a point stereo and the LiDAR disagree on by more is a fault of one of them, not sub-pixel);
///  2. |d(q) - d(p)| <= surfaceGap px: q and p lie on the same surface (no residual crosses an
///     object's edge);
/// and adds it to its disparity: d'(p) = d(p) + sum(w r) / sum(w). The matched surface keeps its
/// shape (slope, the pixels between the scan lines), the LiDAR sets where it lies. Near pixels are
/// left alone: there the parabola is already finer than the metric needs, and KITTI's 3 px / 5 %
/// "correct" is decided by whole-pixel mistakes a sub-pixel shift can only push over the edge.
///
/// Measured with lidar_sgm_eval (docs/RESULTS.md, "LiDAR-anchored sub-pixel disparity"): KITTI142
/// fused, 29 frames: the cloud's 3D F-score at 0.2 m 85.8 -> 92.1 % (40-80 m: 28.6 -> 63.1 %;
/// IP-Basic 91.7 and 62.9), depth MAE 507 -> 423 mm, the 2D tables within 0.03 points.
///
/// Integer sums (weights of 1/1024, residuals in x16 units, 64 bits): the result does not depend
/// on the order of the points or on threads.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {

struct LidarAnchorOptions {
  bool enabled = true;
  /// Pixels whose matched disparity is at most this many px are anchored (KITTI: beyond ~19 m),
  /// in [0, 1024]; 0 anchors none.
  double maxDisparity = 20.0;
  /// The window of points around a pixel: +-halfWidth columns, +-halfHeight rows, each in [0, 16]
  /// (a 64-beam scan's lines are ~5 rows apart at KITTI's focal length: two lines reach a pixel).
  int halfWidth = 4;
  int halfHeight = 5;
  /// Spatial weight exp(-dist^2 / (2 sigma^2)), sigma in [0.5, 16] px; in 1/1024, so a point
  /// farther than about 2.8 sigma weighs nothing (KITTI142: 1.5 px beat 2 and 3 px in 3D; 1 px
  /// gained more at 40-80 m but lost depth RMSE).
  double sigma = 1.5;
  /// |LiDAR - matched| at the point's pixel, in [1/16, 8] px.
  double agreement = 1.0;
  /// |matched at the point - matched at the pixel|, in [0, 8] px.
  double surfaceGap = 0.5;
};

/// Throws std::invalid_argument naming the field when `options` are out of range.
void validate(const LidarAnchorOptions& options);

/// The per-pixel sums, kept between frames by the caller (8 bytes a pixel each: on huge pages,
/// as every large buffer of a frame, huge_page_allocator.hpp).
struct LidarAnchorBuffers {
  HugePageVector<std::int64_t> weightedResidual;  ///< sum of w * r (w in 1/1024, r in x16 units), per pixel
  HugePageVector<std::int64_t> weight;            ///< sum of w
};

/// Adds to each valid pixel of `disparity16` (x16, kInvalidDisparity where none) at most
/// maxDisparity px the weighted mean residual of the agreeing LiDAR `samples` (pixel and x16
/// disparity, in the same image) around it; returns how many pixels moved. Invalid pixels stay
/// invalid; samples outside the image are skipped.
std::size_t anchorToLidar(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                          const LidarAnchorOptions& options, LidarAnchorBuffers& buffers);

}  // namespace lidar_sgm
