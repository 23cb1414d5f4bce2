// Census transform, reference backend: one comparison per bit, as written in the definition.
#include <algorithm>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

constexpr int kHalfWidth = 4;   // 9 columns
constexpr int kHalfHeight = 3;  // 7 rows

template <typename Pixel>
Pixel clampedAt(ImageView<const Pixel> image, int x, int y) {
  // Border pixels repeat, so every pixel gets a full-length census string.
  return image(std::clamp(x, 0, image.width - 1), std::clamp(y, 0, image.height - 1));
}

template <typename Pixel>
void censusTransformImpl(ImageView<const Pixel> image, CensusType type,
                         ImageView<std::uint64_t> census) {
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::uint64_t bits = 0;
      if (type == CensusType::Census9x7) {
        const Pixel centre = image(x, y);
        for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
          for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
            if (dx == 0 && dy == 0) continue;
            bits = (bits << 1) | (clampedAt(image, x + dx, y + dy) < centre ? 1u : 0u);
          }
        }
      } else {
        // Centre-symmetric: compare each pixel of the window's first half with its mirror.
        for (int dy = -kHalfHeight; dy <= 0; ++dy) {
          for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
            if (dy == 0 && dx >= 0) break;
            const Pixel a = clampedAt(image, x + dx, y + dy);
            const Pixel b = clampedAt(image, x - dx, y - dy);
            bits = (bits << 1) | (a < b ? 1u : 0u);
          }
        }
      }
      census(x, y) = bits;
    }
  }
}

}  // namespace

void censusTransform(ImageView<const std::uint8_t> image, CensusType type,
                     ImageView<std::uint64_t> census) {
  censusTransformImpl(image, type, census);
}

void censusTransform(ImageView<const std::uint16_t> image, CensusType type,
                     ImageView<std::uint64_t> census) {
  censusTransformImpl(image, type, census);
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
