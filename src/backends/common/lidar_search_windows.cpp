#include "backends/common/lidar_search_windows.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "backends/common/search_window_rule.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

// The neighbourhood is a box: the extremes over +-1 column first (one pass over the points),
// then over +-rows rows of those, instead of (2 rows + 1) * 3 pixels' points per pixel.
void prepareLidarSearchWindows(const LidarPoints& points, int numDisparities, SearchWindows& windows) {
  // Pass 2 sets every pixel's window: no fill here.
  windows.resize(points.width(), points.height(), numDisparities);
  const std::size_t n = static_cast<std::size_t>(points.width()) * points.height();
  SearchWindows::Scratch& scratch = windows.scratch();
  scratch.lowest16.resize(n);  // no reallocation for a size seen before; pass 1 fills its rows
  scratch.highest16.resize(n);
}

void lidarSearchExtremes(const LidarPoints& points, int y0, int y1, SearchWindows& windows) {
  const int width = points.width();
  SearchWindows::Scratch& scratch = windows.scratch();
  for (int y = y0; y < y1; ++y) {
    std::int16_t* lowest16 = scratch.lowest16.data() + static_cast<std::size_t>(y) * width;
    std::int16_t* highest16 = scratch.highest16.data() + static_cast<std::size_t>(y) * width;
    std::fill(lowest16, lowest16 + width, kSearchNoLowest);
    std::fill(highest16, highest16 + width, kSearchNoHighest);
    // A row's points are contiguous: the pixels without any are skipped by their offsets alone.
    for (int x = 0; x < width; ++x) {
      for (const int* d = points.begin(x, y); d != points.end(x, y); ++d) {
        const std::int16_t value = searchClamp16(*d);
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          lowest16[nx] = std::min(lowest16[nx], value);
          highest16[nx] = std::max(highest16[nx], value);
        }
      }
    }
  }
}

void lidarSearchRowExtremes(int rows, int y, std::int16_t* low16, std::int16_t* high16, const SearchWindows& windows) {
  const int width = windows.width();
  const int height = windows.height();
  const SearchWindows::Scratch& scratch = windows.scratch();
  // The extremes over +-rows rows, a whole row at a time (contiguous: the compiler vectorises it).
  std::fill(low16, low16 + width, kSearchNoLowest);
  std::fill(high16, high16 + width, kSearchNoHighest);
  for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows); ++ny) {
    const std::int16_t* lowRow = scratch.lowest16.data() + static_cast<std::size_t>(ny) * width;
    const std::int16_t* highRow = scratch.highest16.data() + static_cast<std::size_t>(ny) * width;
    for (int x = 0; x < width; ++x) {
      low16[x] = std::min(low16[x], lowRow[x]);
      high16[x] = std::max(high16[x], highRow[x]);
    }
  }
}

void lidarSearchWindowRows(int minDisparity, int rows, int margin, int y0, int y1, std::int16_t* low16,
                           std::int16_t* high16, SearchWindows& windows) {
  const int width = windows.width();
  const int numDisparities = windows.numDisparities();
  for (int y = y0; y < y1; ++y) {
    lidarSearchRowExtremes(rows, y, low16, high16, windows);
    for (int x = 0; x < width; ++x) {
      int first = 0;
      int count = 0;
      searchWindowOf(low16[x], high16[x], minDisparity, numDisparities, margin, first, count);
      windows.set(x, y, first, count);
    }
  }
}

void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows) {
  prepareLidarSearchWindows(points, numDisparities, windows);
  lidarSearchExtremes(points, 0, points.height(), windows);
  SearchWindows::Scratch& scratch = windows.scratch();
  scratch.rowLowest16.resize(static_cast<std::size_t>(points.width()));
  scratch.rowHighest16.resize(static_cast<std::size_t>(points.width()));
  lidarSearchWindowRows(minDisparity, rows, margin, 0, points.height(), scratch.rowLowest16.data(),
                        scratch.rowHighest16.data(), windows);
}

}  // namespace lidar_sgm
