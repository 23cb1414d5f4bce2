// LiDAR matching cost C_L (Eq. 4), reference backend.
#include <algorithm>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity,
               MatchingCostVolume& cost, ImageView<std::uint8_t> support) {
  const int width = points.width();
  const int height = points.height();
  std::vector<int> associated;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // The points of the pixel itself and of its 8 neighbours are associated with it (Sec. III-B).
      associated.clear();
      for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny) {
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          associated.insert(associated.end(), points.begin(nx, ny), points.end(nx, ny));
        }
      }
      for (int d = 0; d < cost.numDisparities(); ++d) {
        const int disparity16 = (minDisparity + d) * kDisparityScale;
        int best = table.cap();
        for (const int dP : associated) best = std::min(best, static_cast<int>(table(disparity16 - dP)));
        // No associated point: no information, the same (zero) cost for every disparity.
        cost(x, y, d) = static_cast<std::uint8_t>(associated.empty() ? 0 : best);
      }
      if (!support.empty()) support(x, y) = associated.empty() ? 0 : 1;
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm

namespace lidar_sgm {
namespace cpu_ref {

void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage) {
  const int width = points.width();
  const int height = points.height();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      bool covered = false;
      for (int ny = std::max(0, y - rows); ny <= std::min(height - 1, y + rows); ++ny) {
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
          if (points.count(nx, ny) > 0) covered = true;
        }
      }
      coverage(x, y) = covered ? 1 : 0;
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
