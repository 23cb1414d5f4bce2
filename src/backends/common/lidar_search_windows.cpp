#include "backends/common/lidar_search_windows.hpp"

#include <algorithm>
#include <climits>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace {

int floorDivide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int ceilDivide(int a, int b) { return -floorDivide(-a, b); }

}  // namespace

void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows) {
  const int width = points.width();
  const int height = points.height();
  windows.resizeFull(width, height, numDisparities);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int lowest16 = INT_MAX;
      int highest16 = INT_MIN;
      for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows); ++ny) {
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          for (const int* d = points.begin(nx, ny); d != points.end(nx, ny); ++d) {
            lowest16 = std::min(lowest16, *d);
            highest16 = std::max(highest16, *d);
          }
        }
      }
      if (lowest16 > highest16) continue;  // no point: the LiDAR does not constrain this pixel
      const int first = std::max(0, floorDivide(lowest16, kDisparityScale) - margin - minDisparity);
      const int last = std::min(numDisparities - 1, ceilDivide(highest16, kDisparityScale) + margin - minDisparity);
      if (first > last) continue;  // every point outside the range: nothing to narrow it to
      const int count = std::min(numDisparities, (last - first + 1 + 15) / 16 * 16);
      windows.set(x, y, std::min(first, numDisparities - count), count);
    }
  }
}

}  // namespace lidar_sgm
