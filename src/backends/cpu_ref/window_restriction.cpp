// The matching cost restricted to the gated search's windows, reference backend.
#include "backends/common/gated_stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void restrictToWindows(const MatchingCostVolume& cost, WindowedMatchingCost& windowed) {
  const SearchWindows& windows = windowed.windows();
  for (int y = 0; y < windows.height(); ++y) {
    for (int x = 0; x < windows.width(); ++x) {
      const int first = windows.first(x, y);
      for (int d = first; d < first + windows.count(x, y); ++d) windowed(x, y, d) = cost(x, y, d);
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
