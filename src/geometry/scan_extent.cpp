#include "lidar_sgm/geometry/scan_extent.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lidar_sgm {
namespace geometry {

std::size_t cropToScanRows(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                           int marginRows, int marginColumns) {
  if (marginRows < 0 || marginColumns < 0) {
    throw std::invalid_argument("cropToScanRows: the margins must be >= 0");
  }
  const int width = disparity16.width;
  const int height = disparity16.height;
  // Per column: the highest (smallest y) and lowest sample row.
  std::vector<int> top(static_cast<std::size_t>(width), std::numeric_limits<int>::max());
  std::vector<int> bottom(static_cast<std::size_t>(width), std::numeric_limits<int>::min());
  for (const LidarSample& s : samples) {
    if (s.x < 0 || s.x >= width || s.y < 0 || s.y >= height) {
      throw std::invalid_argument("cropToScanRows: a sample lies outside the disparity image");
    }
    top[s.x] = std::min(top[s.x], s.y);
    bottom[s.x] = std::max(bottom[s.x], s.y);
  }
  std::size_t cleared = 0;
  for (int x = 0; x < width; ++x) {
    int first = std::numeric_limits<int>::max();
    int last = std::numeric_limits<int>::min();
    for (int xx = std::max(0, x - marginColumns); xx <= std::min(width - 1, x + marginColumns); ++xx) {
      first = std::min(first, top[xx]);
      last = std::max(last, bottom[xx]);
    }
    for (int y = 0; y < height; ++y) {
      // A column without any sample nearby has first > last: everything is cleared.
      const bool inside = first <= last && y >= first - marginRows && y <= last + marginRows;
      if (!inside && disparity16(x, y) != kInvalidDisparity) {
        disparity16(x, y) = kInvalidDisparity;
        ++cleared;
      }
    }
  }
  return cleared;
}

}  // namespace geometry
}  // namespace lidar_sgm
