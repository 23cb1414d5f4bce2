// The right view's winners on the gated search's windows, reference backend (the left-right
// check itself works on indices and is the ungated one, lr_check.cpp).
#include "backends/common/gated_stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void rightDisparityIndex(const WindowedAggregatedCost& sum, int minDisparity, ImageView<std::int16_t> rightIndex) {
  const SearchWindows& windows = sum.windows();
  const int width = sum.width();
  for (int y = 0; y < sum.height(); ++y) {
    for (int xr = 0; xr < width; ++xr) {
      // Read the left volume diagonally; an entry outside its pixel's window is no candidate.
      int best = -1;
      int bestCost = 0;
      for (int d = 0; d < sum.numDisparities(); ++d) {
        const int x = xr + minDisparity + d;
        if (x < 0 || x >= width || !windows.contains(x, y, d)) continue;
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

}  // namespace cpu_ref
}  // namespace lidar_sgm
