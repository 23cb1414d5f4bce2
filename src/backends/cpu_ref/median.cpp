// Median filter over valid disparities, reference backend.
#include <algorithm>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out) {
  const int radius = size / 2;
  std::vector<std::int16_t> window;
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      if (radius == 0 || in(x, y) == kInvalidDisparity) {
        out(x, y) = in(x, y);  // an invalid pixel is not filled: the median removes outliers only
        continue;
      }
      window.clear();
      for (int ny = std::max(0, y - radius); ny <= std::min(in.height - 1, y + radius); ++ny) {
        for (int nx = std::max(0, x - radius); nx <= std::min(in.width - 1, x + radius); ++nx) {
          if (in(nx, ny) != kInvalidDisparity) window.push_back(in(nx, ny));
        }
      }
      std::sort(window.begin(), window.end());
      out(x, y) = window[(window.size() - 1) / 2];  // lower median for even counts
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
