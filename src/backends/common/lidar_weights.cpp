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

int lidarDensity256(ImageView<const std::uint16_t> distance) {
  long long touched = 0;
  long long scan = 0;
  for (int y = 0; y < distance.height; ++y) {
    for (int x = 0; x < distance.width; ++x) {
      touched += distance(x, y) <= 1 ? 1 : 0;
      scan += distance(x, y) <= kAdaptiveReach ? 1 : 0;
    }
  }
  return scan == 0 ? 0 : static_cast<int>(touched * 256 / scan);
}

int densityFactor256(int density256) {
  const int range = kDenseDensity256 - kSparseDensity256;
  return std::clamp((kDenseDensity256 - density256) * 256 / range, 64, 256);
}

int lidarWeight(const Parameters& params, int distance, int densityFactor256) {
  const int fixed = alphaWeight(params.alpha);
  if (params.alphaMode == AlphaMode::Fixed) return fixed;
  // The stereo share of Eq. 5, 256 - w, shrinks towards the scan and with the scan's density.
  const int nearness = std::clamp(distance, 1, kAdaptiveReach);
  return 256 - (256 - fixed) * nearness * densityFactor256 / (kAdaptiveReach * 256);
}

void lidarWeights(const LidarPoints& points, const Parameters& params, ImageView<std::uint16_t> weights) {
  // The distances first, in place (no allocation per frame), then one table lookup per pixel:
  // with the frame's density fixed, the weight depends on the distance only.
  lidarDistance(points, weights);
  const int factor = densityFactor256(lidarDensity256(weights));
  std::uint16_t table[kMaxLidarDistance + 1];
  for (int d = 0; d <= kMaxLidarDistance; ++d) table[d] = static_cast<std::uint16_t>(lidarWeight(params, d, factor));
  for (int y = 0; y < weights.height; ++y) {
    for (int x = 0; x < weights.width; ++x) weights(x, y) = table[weights(x, y)];
  }
}

}  // namespace lidar_sgm
