#pragma once
/// @file lidar_weights.hpp  The LiDAR weight of Eq. 5 per pixel, w(p) out of 256 (range-adaptive
/// fusion, the paper's future work): computed once per frame, on the host, in integers, and shared
/// as data by every backend, so that all of them fuse with the same weights bit for bit.

#include <cstdint>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {

/// Distances are capped here [px]: every pixel this far from the scan is treated alike.
constexpr int kMaxLidarDistance = 255;

/// The adaptive weight reaches the fixed alpha's at this chessboard distance [px] from the
/// nearest LiDAR point (about the half gap between two beams of a 64-beam scan in a KITTI image).
constexpr int kAdaptiveReach = 4;

/// For every pixel: the chessboard distance [px] to the nearest pixel that holds a LiDAR point
/// (0 on such a pixel, kMaxLidarDistance when there is none that close). Two raster passes
/// (the exact chessboard distance transform).
void lidarDistance(const LidarPoints& points, ImageView<std::uint16_t> distance);

/// The LiDAR weight of one pixel out of 256 from its distance to the scan (lidarDistance):
/// alphaMode Fixed: alphaWeight(alpha) everywhere. Adaptive: the stereo share 256 - w shrinks
/// towards the LiDAR, s = (256 - alphaWeight(alpha)) * clamp(distance, 1, kAdaptiveReach) /
/// kAdaptiveReach (rounded down), so alpha is the weight kAdaptiveReach px and more away from the
/// scan. Between the beams of a dense scan every pixel is near a point and the weight rises (a
/// 128-beam scan weighs more than a 64-beam one); above the scan stereo keeps the fixed share.
int lidarWeight(const Parameters& params, int distance);

/// w(p) = lidarWeight(params, distance(p)) of every pixel, in [0, 256]; `weights` has the points'
/// size (std::invalid_argument otherwise).
void lidarWeights(const LidarPoints& points, const Parameters& params, ImageView<std::uint16_t> weights);

}  // namespace lidar_sgm
