// The per-pixel LiDAR weight of Eq. 5 (range-adaptive fusion), shared by every backend.
#include "backends/common/lidar_weights.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "backends/common/stages.hpp"

namespace lidar_sgm {

void lidarDistance(const LidarPoints& points, ImageView<std::uint16_t> distance) {
  const int width = points.width();
  const int height = points.height();
  if (distance.width != width || distance.height != height) {
    throw std::invalid_argument("lidarDistance: the distance image is " + std::to_string(distance.width) + "x" +
                                std::to_string(distance.height) + ", the LiDAR points' image " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  const auto at = [&](int x, int y) -> int {
    return x < 0 || x >= width || y < 0 || y >= height ? kMaxLidarDistance : distance(x, y);
  };
  // Forward pass: the neighbours already visited (left, and the row above).
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int d = points.count(x, y) > 0 ? 0 : kMaxLidarDistance;
      d = std::min({d, at(x - 1, y) + 1, at(x - 1, y - 1) + 1, at(x, y - 1) + 1, at(x + 1, y - 1) + 1});
      distance(x, y) = static_cast<std::uint16_t>(std::min(d, kMaxLidarDistance));
    }
  }
  // Backward pass: right, and the row below.
  for (int y = height - 1; y >= 0; --y) {
    for (int x = width - 1; x >= 0; --x) {
      const int d = std::min({static_cast<int>(distance(x, y)), at(x + 1, y) + 1, at(x + 1, y + 1) + 1,
                              at(x, y + 1) + 1, at(x - 1, y + 1) + 1});
      distance(x, y) = static_cast<std::uint16_t>(std::min(d, kMaxLidarDistance));
    }
  }
}

int lidarWeight(const Parameters& params, int distance) {
  const int fixed = alphaWeight(params.alpha);
  if (params.alphaMode == AlphaMode::Fixed) return fixed;
  // The stereo share of Eq. 5 falls linearly towards the scan: SGM's paths carry a LiDAR
  // disparity well over a few pixels, and the stereo cost there mostly adds noise.
  const int stereoShare = (256 - fixed) * std::clamp(distance, 1, kAdaptiveReach) / kAdaptiveReach;
  return 256 - stereoShare;
}

void lidarWeights(const LidarPoints& points, const Parameters& params, ImageView<std::uint16_t> weights) {
  // The distances first, in place (no allocation per frame), then one table lookup per pixel:
  // the weight depends on the distance only.
  lidarDistance(points, weights);
  std::uint16_t table[kMaxLidarDistance + 1];
  for (int d = 0; d <= kMaxLidarDistance; ++d) table[d] = static_cast<std::uint16_t>(lidarWeight(params, d));
  for (int y = 0; y < weights.height; ++y) {
    for (int x = 0; x < weights.width; ++x) weights(x, y) = table[weights(x, y)];
  }
}

}  // namespace lidar_sgm
