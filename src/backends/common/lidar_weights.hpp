#pragma once
/// @file lidar_weights.hpp  The LiDAR weight of Eq. 5 per pixel, w(p) out of 256 (range-adaptive
/// fusion, the paper's future work): computed once per frame, on the host, in integers, and shared
/// as data by every backend, so that all of them fuse with the same weights bit for bit.
///
/// Adaptive weights (Parameters::alphaMode): the stereo share of Eq. 5, 256 - w, is the fixed
/// alpha's, (256 - alphaWeight(alpha)), scaled by two factors out of 256:
/// - distance: clamp(dist, 1, kAdaptiveReach) / kAdaptiveReach, dist = the chessboard distance to
///   the nearest pixel holding a LiDAR point. SGM's paths carry a LiDAR disparity well over a few
///   pixels, so near the scan the stereo cost mostly adds noise; far from it (above the top beam)
///   stereo keeps the fixed share.
/// - density: the frame's share of the scan area (pixels within kAdaptiveReach px of a point)
///   that lies within 1 px of a point, rho. A dense scan (measured: 128 synthetic beams rho 0.63,
///   64 synthetic beams 0.45, KITTI-like 64-beam frames 0.25-0.39) leaves short gaps that SGM
///   interpolates almost perfectly: the factor falls linearly from 1 at rho <= kSparseDensity256
///   to 1/4 at rho >= kDenseDensity256. Measured per protocol in docs/RESULTS.md ("Range-adaptive
///   fusion"), with the variants that did not help (a range term among them).

#include <cstdint>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {

/// Distances are capped here [px]: every pixel this far from the scan is treated alike.
constexpr int kMaxLidarDistance = 255;
/// The adaptive stereo share reaches the fixed alpha's this far [px] from the nearest point.
constexpr int kAdaptiveReach = 8;
/// Scan densities rho (out of 256) between which the density factor falls from 1 to 1/4.
constexpr int kSparseDensity256 = 102;  // 0.4
constexpr int kDenseDensity256 = 204;   // 0.8

/// For every pixel: the chessboard distance [px] to the nearest pixel that holds a LiDAR point
/// (0 on such a pixel, kMaxLidarDistance when there is none that close), by two raster passes
/// (the exact chessboard distance transform). `distance` has the points' size
/// (std::invalid_argument otherwise).
void lidarDistance(const LidarPoints& points, ImageView<std::uint16_t> distance);

/// rho out of 256: the pixels within 1 px of a point over those within kAdaptiveReach px, from
/// lidarDistance's image (0 when no pixel is that close).
int lidarDensity256(ImageView<const std::uint16_t> distance);

/// The density factor out of 256 (see the file comment): 256 at rho <= kSparseDensity256, 64 at
/// rho >= kDenseDensity256, linear (rounded down) between.
int densityFactor256(int density256);

/// The LiDAR weight of one pixel out of 256. alphaMode Fixed: alphaWeight(alpha) whatever the
/// distance and density. Adaptive: 256 - (256 - alphaWeight(alpha)) * clamp(distance, 1,
/// kAdaptiveReach) * densityFactor256 / (kAdaptiveReach * 256), rounded down.
int lidarWeight(const Parameters& params, int distance, int densityFactor256);

/// w(p) of every pixel, in [0, 256]: the distances in place, then lidarWeight with the frame's
/// density factor. `weights` has the points' size.
void lidarWeights(const LidarPoints& points, const Parameters& params, ImageView<std::uint16_t> weights);

}  // namespace lidar_sgm
