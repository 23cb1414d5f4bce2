// The backend's part of the confidence (core/confidence.hpp), reference backend: the two inputs
// that need the aggregated cost volume S, which only the backend holds.
#include <algorithm>
#include <cstdlib>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost) {
  const int D = sum.numDisparities();
  for (int y = 0; y < sum.height(); ++y) {
    for (int x = 0; x < sum.width(); ++x) {
      const int best = bestIndex(x, y);
      if (best < 0) {
        margin(x, y) = 0;
        bestCost(x, y) = 0;
        continue;
      }
      const std::uint16_t* S = sum.at(x, y);
      bestCost(x, y) = S[best];
      int second = -1;  // the lowest cost outside the winner's +-1
      for (int d = 0; d < D; ++d) {
        if (std::abs(d - best) > 1 && (second < 0 || S[d] < second)) second = S[d];
      }
      if (second < 0) {
        margin(x, y) = 255;
        continue;
      }
      const int value = (256 * (second - S[best])) / std::max(second, 1);
      margin(x, y) = static_cast<std::uint8_t>(std::min(value, 255));
    }
  }
}

void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference) {
  for (int y = 0; y < bestIndex.height; ++y) {
    for (int x = 0; x < bestIndex.width; ++x) {
      const int best = bestIndex(x, y);
      const int xr = x - (minDisparity + best);
      if (best < 0 || xr < 0 || xr >= bestIndex.width || rightIndex(xr, y) < 0) {
        difference(x, y) = kNoCounterpartDifference;
        continue;
      }
      difference(x, y) = static_cast<std::uint8_t>(std::min(std::abs(rightIndex(xr, y) - best), 254));
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
