#include "texture_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace lidar_sgm {

TextureMap::TextureMap(const GrayImageView& left, int radius) : radius_(radius) {
  if (left.empty()) return;
  width_ = left.width();
  height_ = left.height();
  levels_.resize(static_cast<std::size_t>(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      levels_[index(x, y)] = left.gray8.empty() ? static_cast<std::uint8_t>(left.gray16(x, y) >> 8) : left.gray8(x, y);
    }
  }
  const std::size_t stride = static_cast<std::size_t>(width_) + 1;
  integral_.assign(stride * (static_cast<std::size_t>(height_) + 1), 0);
  for (int y = 0; y < height_; ++y) {
    std::int64_t rowSum = 0;
    for (int x = 0; x < width_; ++x) {
      const int c = level8(x, y);
      const int dx = x + 1 < width_ ? std::abs(level8(x + 1, y) - c) : 0;
      const int dy = y + 1 < height_ ? std::abs(level8(x, y + 1) - c) : 0;
      rowSum += dx + dy;
      integral_[(y + 1) * stride + x + 1] = integral_[y * stride + x + 1] + rowSum;
    }
  }
}

bool TextureMap::meanGradientBelow(int x, int y, double threshold) const {
  const int x0 = std::max(0, x - radius_);
  const int x1 = std::min(width_ - 1, x + radius_) + 1;
  const int y0 = std::max(0, y - radius_);
  const int y1 = std::min(height_ - 1, y + radius_) + 1;
  const std::size_t stride = static_cast<std::size_t>(width_) + 1;
  const std::int64_t sum = integral_[y1 * stride + x1] - integral_[y0 * stride + x1] - integral_[y1 * stride + x0] +
                           integral_[y0 * stride + x0];
  const std::int64_t area = static_cast<std::int64_t>(x1 - x0) * (y1 - y0);
  // sum / area < threshold, in integers with the threshold in 1/256 levels.
  const std::int64_t threshold256 = std::llround(threshold * 256.0);
  return sum * 256 < threshold256 * area;
}

}  // namespace lidar_sgm
