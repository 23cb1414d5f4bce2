#include "lidar_sgm/pipeline/min_confidence.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lidar_sgm {

int confidenceThreshold(double minConfidence) {
  if (!(minConfidence >= 0.0 && minConfidence <= 1.0)) {
    throw std::invalid_argument("minConfidence = " + std::to_string(minConfidence) + ": must be in [0, 1]");
  }
  return static_cast<int>(std::ceil(255.0 * minConfidence - 1e-9));
}

void applyMinConfidence(ImageView<std::int16_t> disparity, ImageView<std::uint8_t> confidence, double minConfidence) {
  const int threshold = confidenceThreshold(minConfidence);
  if (disparity.width != confidence.width || disparity.height != confidence.height) {
    throw std::invalid_argument("applyMinConfidence: the disparity and confidence images differ in size");
  }
  if (threshold == 0) return;
  for (int y = 0; y < disparity.height; ++y) {
    for (int x = 0; x < disparity.width; ++x) {
      if (confidence(x, y) >= threshold) continue;
      disparity(x, y) = kInvalidDisparity;
      confidence(x, y) = 0;
    }
  }
}

}  // namespace lidar_sgm
