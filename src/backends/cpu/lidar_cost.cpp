// LiDAR matching cost C_L (Eq. 4), fast CPU backend. Streamed: computed per row from the points
// of its three rows instead of a second cost volume. A point's cost is below the cap only
// within +-table.entries().size() / 16 px of its disparity (about +-2 px for sigma = 2), so
// each point touches a handful of disparities, not all D.
#include <algorithm>
#include <cstring>
#include <vector>

#include "backends/common/lidar_search_windows.hpp"
#include "backends/common/search_window_rule.hpp"
#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

namespace lidar_sgm {
namespace cpu {
LidarCostRows::LidarCostRows(const LidarCostTable& table)
    : cap_(table.cap()), reach_(static_cast<int>(table.entries().size())) {
  // table(16 j - reach - r) is below the cap only while |16 j - reach - r| < reach, i.e.
  // 16 j < 2 reach + r <= 2 reach + 15: j <= (2 reach + 14) / 16.
  width_ = ((2 * reach_ + 14) / kDisparityScale + 1 + 15) / 16 * 16;
  rows_.resize(static_cast<std::size_t>(kDisparityScale) * width_);
  for (int r = 0; r < kDisparityScale; ++r) {
    for (int j = 0; j < width_; ++j) rows_[static_cast<std::size_t>(r) * width_ + j] = table(kDisparityScale * j - reach_ - r);
  }
}

namespace {

// cost[j] = min(cost[j], row[j]) for j in [0, n), n a multiple of 16 (a vector minimum).
void minimumInto(std::uint8_t* __restrict cost, const std::uint8_t* __restrict row, int n) {
  for (int b = 0; b < n; b += 16) {
    for (int k = 0; k < 16; ++k) cost[b + k] = std::min(cost[b + k], row[b + k]);
  }
}

}  // namespace

void lidarCostRow(const LidarPoints& points, const LidarCostRows& rows, int y, int x0, int x1, int minDisparity,
                  int numDisparities, const std::uint8_t* touched, std::uint8_t* cost) {
  const int width = points.width();
  const int height = points.height();
  const int reach = rows.reach();  // |diff16| >= reach costs the cap
  const int span = rows.width();
  const auto D = static_cast<std::size_t>(numDisparities);
  for (int x = x0; x < x1; ++x) {
    if (touched[x] != 0) std::memset(cost + static_cast<std::size_t>(x - x0) * D, rows.cap(), D);
  }
  // The points of a pixel and of its 8 neighbours are associated with it (Sec. III-B): each point
  // of rows y-1 .. y+1 in columns x0-1 .. x1 takes the minimum into its own column's pixel and
  // the two beside it. A row's points lie side by side in pixel order (LidarPoints), so the run of
  // them is read at once, not nine cells per pixel, most of them empty. Every pixel a point reaches
  // is touched (lidarTouchedRow): the cap was set above.
  for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny) {
    const RowPoints run = rowPoints(points, ny, std::max(0, x0 - 1), std::min(width, x1 + 1));
    for (int i = run.begin; i < run.end; ++i) {
      const int px = run.column(i);
      const int dP = run.disparity16[i];
      const int q = floorDivide(dP - reach, kDisparityScale);
      const std::uint8_t* row = rows.row(dP - reach - kDisparityScale * q);
      const int first = q - minDisparity;  // the index of row[0] in a pixel's costs
      for (int nx = std::max(x0, px - 1); nx <= std::min(x1 - 1, px + 1); ++nx) {
        std::uint8_t* c = cost + static_cast<std::size_t>(nx - x0) * D;
        if (first >= 0 && first + span <= numDisparities) {
          minimumInto(c + first, row, span);
        } else {
          // At the ends of the range: the row's part inside it (the rest costs the cap anyway).
          for (int j = std::max(0, -first); j < std::min(span, numDisparities - first); ++j) {
            c[first + j] = std::min(c[first + j], row[j]);
          }
        }
      }
    }
  }
}

void lidarTouchedRow(const LidarPoints& points, int y, std::uint8_t* touched) {
  const int width = points.width();
  std::fill(touched, touched + width, std::uint8_t{0});
  // From each row's run of points (as lidarCostRow), not from every pixel's count.
  for (int ny = std::max(0, y - 1); ny <= std::min(points.height() - 1, y + 1); ++ny) {
    const RowPoints run = rowPoints(points, ny, 0, width);
    for (int i = run.begin; i < run.end; ++i) {
      const int x = run.column(i);
      for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) touched[nx] = 1;
    }
  }
}

void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity, MatchingCostVolume& cost,
               ImageView<std::uint8_t> support, int threads) {
  const LidarCostRows rows(table);
  const int width = points.width();
  parallelRanges(points.height(), threads, [&](int y0, int y1) {
    std::vector<std::uint8_t> touched(static_cast<std::size_t>(width));
    for (int y = y0; y < y1; ++y) {
      lidarTouchedRow(points, y, touched.data());
      std::uint8_t* row = cost.at(0, y);  // the row's pixels lie side by side, D costs each
      lidarCostRow(points, rows, y, 0, width, minDisparity, cost.numDisparities(), touched.data(), row);
      for (int x = 0; x < width; ++x) {
        // No associated point: no information, the same (zero) cost for every disparity.
        if (touched[x] == 0) std::memset(cost.at(x, y), 0, static_cast<std::size_t>(cost.numDisparities()));
        if (!support.empty()) support(x, y) = touched[x];
      }
    }
  });
}

void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage, int threads) {
  const int width = points.width();
  const int height = points.height();
  parallelRanges(height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < width; ++x) {
        bool covered = false;
        for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows) && !covered; ++ny) {
          for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
            if (points.count(nx, ny) > 0) covered = true;
          }
        }
        coverage(x, y) = covered ? 1 : 0;
      }
    }
  });
}

namespace {

// lidarSearchExtremes (lidar_search_windows.hpp) from each row's run of points, as lidarCostRow:
// the same extremes, without visiting the pixels that hold none.
void searchExtremesOfRows(const LidarPoints& points, int y0, int y1, SearchWindows& windows) {
  const int width = points.width();
  SearchWindows::Scratch& scratch = windows.scratch();
  for (int y = y0; y < y1; ++y) {
    const std::size_t rowStart = static_cast<std::size_t>(y) * width;
    std::int16_t* lowest16 = scratch.lowest16.data() + rowStart;
    std::int16_t* highest16 = scratch.highest16.data() + rowStart;
    std::fill(lowest16, lowest16 + width, kSearchNoLowest);
    std::fill(highest16, highest16 + width, kSearchNoHighest);
    const RowPoints run = rowPoints(points, y, 0, width);
    for (int i = run.begin; i < run.end; ++i) {
      const int x = run.column(i);
      const std::int16_t value = searchClamp16(run.disparity16[i]);
      for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
        lowest16[nx] = std::min(lowest16[nx], value);
        highest16[nx] = std::max(highest16[nx], value);
      }
    }
  }
}

}  // namespace

// lidarSearchWindows' two passes, each with its rows split among the threads (single-threaded,
// the vertical pass's 2 * rows + 1 rows of extremes per row cost more than the gate saved); each
// range's two rows of that pass in the windows' scratch.
void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows, int threads) {
  const int height = points.height();
  prepareLidarSearchWindows(points, numDisparities, windows);
  parallelRanges(height, threads, [&](int y0, int y1) { searchExtremesOfRows(points, y0, y1, windows); });
  const std::size_t width = static_cast<std::size_t>(points.width());
  SearchWindows::Scratch& scratch = windows.scratch();
  scratch.rowLowest16.resize(width * static_cast<std::size_t>(rangeCount(height, threads)));
  scratch.rowHighest16.resize(width * static_cast<std::size_t>(rangeCount(height, threads)));
  parallelParts(height, threads, [&](int part, int y0, int y1) {
    const std::size_t offset = width * static_cast<std::size_t>(part);
    searchWindowRows(points, minDisparity, rows, margin, y0, y1, scratch.rowLowest16.data() + offset,
                     scratch.rowHighest16.data() + offset, windows);
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
