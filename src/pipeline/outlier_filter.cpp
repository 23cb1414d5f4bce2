#include "lidar_sgm/pipeline/outlier_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace lidar_sgm {

void validate(const OutlierFilterOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("OutlierFilterOptions: " + what); };
  if (o.radius < 1 || o.radius > 8) fail("radius must be in [1, 8], got " + std::to_string(o.radius));
  if (!(o.relativeTolerance >= 0.0 && o.relativeTolerance <= 1.0)) {
    fail("relativeTolerance must be in [0, 1], got " + std::to_string(o.relativeTolerance));
  }
  if (!(o.minTolerance >= 0.0 && o.minTolerance <= 64.0)) {
    fail("minTolerance must be in [0, 64] px, got " + std::to_string(o.minTolerance));
  }
  const int window = (2 * o.radius + 1) * (2 * o.radius + 1) - 1;
  if (o.minNeighbours < 0 || o.minNeighbours > window) {
    fail("minNeighbours must be in [0, " + std::to_string(window) + "] for radius " + std::to_string(o.radius) +
         ", got " + std::to_string(o.minNeighbours));
  }
}

std::size_t removeOutliers(ImageView<std::int16_t> disparity16, const OutlierFilterOptions& options) {
  validate(options);
  if (!options.enabled || options.minNeighbours == 0) return 0;
  const int width = disparity16.width;
  const int height = disparity16.height;
  std::vector<std::int16_t> input(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) std::copy(disparity16.row(y), disparity16.row(y) + width, input.begin() + y * width);
  const auto at = [&input, width](int x, int y) { return input[static_cast<std::size_t>(y) * width + x]; };
  // Tolerances in x16 units; the relative one in 1/1024 (integer products, no rounding order).
  const int minTolerance16 = static_cast<int>(std::lround(options.minTolerance * kDisparityScale));
  const long relative1024 = std::lround(options.relativeTolerance * 1024.0);
  const int r = options.radius;

  std::size_t removed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int d = at(x, y);
      if (d == kInvalidDisparity) continue;
      const long tolerance = std::max<long>(minTolerance16, (relative1024 * std::abs(d)) / 1024);
      int similar = 0;
      for (int yy = std::max(0, y - r); yy <= std::min(height - 1, y + r) && similar < options.minNeighbours; ++yy) {
        for (int xx = std::max(0, x - r); xx <= std::min(width - 1, x + r); ++xx) {
          const int q = at(xx, yy);
          if ((xx == x && yy == y) || q == kInvalidDisparity) continue;
          if (std::abs(q - d) <= tolerance) ++similar;
        }
      }
      if (similar < options.minNeighbours) {
        disparity16(x, y) = kInvalidDisparity;
        ++removed;
      }
    }
  }
  return removed;
}

}  // namespace lidar_sgm
