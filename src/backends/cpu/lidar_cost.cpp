// LiDAR matching cost C_L (Eq. 4), fast CPU backend. Streamed: computed per pixel from the
// few points around it instead of a second cost volume. A point's cost is below the cap only
// within +-table.entries().size() / 16 px of its disparity (about +-2 px for sigma = 2), so
// each point touches a handful of disparities, not all D.
#include <algorithm>
#include <cstring>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

namespace lidar_sgm {
namespace cpu {
namespace {

int floorDivide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

bool lidarCostPixel(const LidarPoints& points, const LidarCostTable& table, int x, int y, int minDisparity,
                    int numDisparities, std::uint8_t* cost) {
  const int width = points.width();
  const int height = points.height();
  const int reach = static_cast<int>(table.entries().size());  // |diff16| >= reach costs the cap
  bool touched = false;
  std::memset(cost, table.cap(), static_cast<std::size_t>(numDisparities));
  // The points of the pixel itself and of its 8 neighbours are associated with it (Sec. III-B).
  for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny) {
    for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
      for (const int* p = points.begin(nx, ny); p != points.end(nx, ny); ++p) {
        touched = true;
        const int dP = *p;
        const int dBegin = std::max(0, floorDivide(dP - reach, kDisparityScale) - minDisparity);
        const int dEnd = std::min(numDisparities - 1, floorDivide(dP + reach, kDisparityScale) + 1 - minDisparity);
        for (int d = dBegin; d <= dEnd; ++d) {
          const std::uint8_t c = table((minDisparity + d) * kDisparityScale - dP);
          if (c < cost[d]) cost[d] = c;
        }
      }
    }
  }
  // No associated point: no information, the same (zero) cost for every disparity.
  if (!touched) std::memset(cost, 0, static_cast<std::size_t>(numDisparities));
  return touched;
}

void lidarTouchedRow(const LidarPoints& points, int y, std::uint8_t* touched) {
  const int width = points.width();
  std::fill(touched, touched + width, std::uint8_t{0});
  for (int ny = std::max(0, y - 1); ny <= std::min(points.height() - 1, y + 1); ++ny) {
    for (int x = 0; x < width; ++x) {
      if (points.count(x, ny) == 0) continue;
      for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) touched[nx] = 1;
    }
  }
}

void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity, MatchingCostVolume& cost,
               ImageView<std::uint8_t> support, int threads) {
  parallelRanges(points.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < points.width(); ++x) {
        const bool touched = lidarCostPixel(points, table, x, y, minDisparity, cost.numDisparities(), cost.at(x, y));
        if (!support.empty()) support(x, y) = touched ? 1 : 0;
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

}  // namespace cpu
}  // namespace lidar_sgm
