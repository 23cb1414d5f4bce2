// Left-right consistency check, reference backend.
#include <cstdlib>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity,
                         ImageView<std::int16_t> rightIndex) {
  const int width = sum.width();
  const int D = sum.numDisparities();
  for (int y = 0; y < sum.height(); ++y) {
    for (int xr = 0; xr < width; ++xr) {
      // The right pixel xr is seen by left pixel xr + disparity: read the left volume diagonally.
      int best = -1;
      int bestCost = 0;
      for (int d = 0; d < D; ++d) {
        const int x = xr + minDisparity + d;
        if (x < 0 || x >= width) continue;
        const int cost = sum(x, y, d);
        if (best < 0 || cost < bestCost) {
          best = d;
          bestCost = cost;
        }
      }
      rightIndex(xr, y) = static_cast<std::int16_t>(best);
    }
  }
}

void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                    bool keepNoCounterpart) {
  for (int y = 0; y < rightIndex.height; ++y) {
    for (int x = 0; x < rightIndex.width; ++x) {
      const int best = disparity.bestIndex(x, y);
      if (best < 0) continue;
      bool keep = true;
      const int xr = x - (minDisparity + best);
      if (xr < 0 || xr >= rightIndex.width) {
        keep = keepNoCounterpart;  // the right camera cannot see it: the check has nothing to compare
      } else if (!support.empty() && support(x, y) != 0) {
        keep = true;               // a LiDAR point measured it; the check would only lose density
      } else {
        const int right = rightIndex(xr, y);
        keep = right >= 0 && std::abs(right - best) <= disp12MaxDiff;
      }
      if (!keep) {
        disparity.disparity16(x, y) = kInvalidDisparity;
        disparity.bestIndex(x, y) = -1;
      }
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
