// The peak-ratio margin on the gated search's windows, reference backend.
#include <algorithm>
#include <cstdlib>

#include "backends/common/gated_stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void peakRatioMargin(const WindowedAggregatedCost& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost) {
  const SearchWindows& windows = sum.windows();
  for (int y = 0; y < sum.height(); ++y) {
    for (int x = 0; x < sum.width(); ++x) {
      const int best = bestIndex(x, y);
      if (best < 0) {
        margin(x, y) = 0;
        bestCost(x, y) = 0;
        continue;
      }
      const int S1 = sum(x, y, best);
      bestCost(x, y) = static_cast<std::uint16_t>(S1);
      int second = -1;  // the lowest cost in the window outside the winner's +-1
      const int first = windows.first(x, y);
      for (int d = first; d < first + windows.count(x, y); ++d) {
        if (std::abs(d - best) > 1 && (second < 0 || sum(x, y, d) < second)) second = sum(x, y, d);
      }
      if (second < 0) {
        margin(x, y) = 255;
        continue;
      }
      const int value = (256 * (second - S1)) / std::max(second, 1);
      margin(x, y) = static_cast<std::uint8_t>(std::min(value, 255));
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
