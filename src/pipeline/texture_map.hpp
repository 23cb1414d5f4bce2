#pragma once
// The left image's local texture: the mean absolute gradient in a square window, from an
// integral image (integers, so every query is exact and deterministic).

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

class TextureMap {
 public:
  /// Empty `left` -> an empty map. 16-bit images are read by their high byte (8-bit levels).
  TextureMap(const GrayImageView& left, int radius);

  bool empty() const { return width_ == 0; }
  /// The pixel's intensity in 8-bit levels.
  int level8(int x, int y) const { return levels_[index(x, y)]; }
  /// Whether the mean of |I(x+1,y) - I(x,y)| + |I(x,y+1) - I(x,y)| over the window around (x, y)
  /// (clipped at the border) is below `threshold` levels per pixel.
  bool meanGradientBelow(int x, int y, double threshold) const;

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int width_ = 0;
  int height_ = 0;
  int radius_ = 0;
  std::vector<std::uint8_t> levels_;
  std::vector<std::int64_t> integral_;  ///< (width+1) x (height+1) sums of the gradient
};

}  // namespace lidar_sgm
