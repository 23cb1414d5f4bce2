#include "backends/common/lidar_search_windows.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace {

int floorDivide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int ceilDivide(int a, int b) { return -floorDivide(-a, b); }

constexpr std::int16_t kNoLowest = std::numeric_limits<std::int16_t>::max();
constexpr std::int16_t kNoHighest = std::numeric_limits<std::int16_t>::min();

// A point's x16 disparity in 16 bits. Clamping changes no window: the range's ends, x16, lie
// within +-16384 (minDisparity and numDisparities are at most 512 in magnitude) and the margin is
// at most 512 px, so a value beyond +-32767 and its clamped value fall on the same side of the
// range, with the same window.
std::int16_t clamp16(int disparity16) {
  return static_cast<std::int16_t>(std::clamp<int>(disparity16, kNoHighest, kNoLowest));
}

}  // namespace

void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows) {
  const int width = points.width();
  const int height = points.height();
  windows.resizeFull(width, height, numDisparities);
  // The neighbourhood is a box: the extremes over +-1 column first (one pass over the points),
  // then over +-rows rows of those, instead of (2 rows + 1) * 3 pixels' points per pixel.
  const std::size_t n = static_cast<std::size_t>(width) * height;
  SearchWindows::Scratch& scratch = windows.scratch();
  std::vector<std::int16_t>& lowest16 = scratch.lowest16;
  std::vector<std::int16_t>& highest16 = scratch.highest16;
  lowest16.assign(n, kNoLowest);  // no reallocation for a size seen before
  highest16.assign(n, kNoHighest);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (const int* d = points.begin(x, y); d != points.end(x, y); ++d) {
        const std::int16_t value = clamp16(*d);
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          const std::size_t i = static_cast<std::size_t>(y) * width + nx;
          lowest16[i] = std::min(lowest16[i], value);
          highest16[i] = std::max(highest16[i], value);
        }
      }
    }
  }
  std::vector<std::int16_t>& low16 = scratch.rowLowest16;
  std::vector<std::int16_t>& high16 = scratch.rowHighest16;
  low16.resize(static_cast<std::size_t>(width));
  high16.resize(static_cast<std::size_t>(width));
  for (int y = 0; y < height; ++y) {
    // The extremes over +-rows rows, a whole row at a time (contiguous: the compiler vectorises it).
    std::fill(low16.begin(), low16.end(), kNoLowest);
    std::fill(high16.begin(), high16.end(), kNoHighest);
    for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows); ++ny) {
      const std::int16_t* lowRow = lowest16.data() + static_cast<std::size_t>(ny) * width;
      const std::int16_t* highRow = highest16.data() + static_cast<std::size_t>(ny) * width;
      for (int x = 0; x < width; ++x) {
        low16[x] = std::min(low16[x], lowRow[x]);
        high16[x] = std::max(high16[x], highRow[x]);
      }
    }
    for (int x = 0; x < width; ++x) {
      if (low16[x] > high16[x]) continue;  // no point: the LiDAR does not constrain this pixel
      const int first = std::max(0, floorDivide(low16[x], kDisparityScale) - margin - minDisparity);
      const int last = std::min(numDisparities - 1, ceilDivide(high16[x], kDisparityScale) + margin - minDisparity);
      if (first > last) continue;  // every point outside the range: nothing to narrow it to
      const int count = std::min(numDisparities, (last - first + 1 + 15) / 16 * 16);
      windows.set(x, y, std::min(first, numDisparities - count), count);
    }
  }
}

}  // namespace lidar_sgm
