// SGM cost aggregation (Eq. 1) on the gated search's windows, reference backend: one full
// path-cost volume per direction, as the ungated aggregation.
#include <algorithm>

#include "backends/common/gated_stages.hpp"
#include "backends/common/path_directions.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

// L_r for every pixel along direction r, in the order that visits p - r before p.
void aggregateDirection(const WindowedMatchingCost& cost, PathDirection r, int P1, int P2,
                        WindowedAggregatedCost& pathCost) {
  const SearchWindows& windows = cost.windows();
  const int width = cost.width();
  const int height = cost.height();
  for (int i = 0; i < height; ++i) {
    const int y = r.dy >= 0 ? i : height - 1 - i;
    for (int j = 0; j < width; ++j) {
      const int x = r.dx >= 0 ? j : width - 1 - j;
      const int px = x - r.dx;
      const int py = y - r.dy;
      const int first = windows.first(x, y);
      const int count = windows.count(x, y);
      if (px < 0 || px >= width || py < 0 || py >= height) {
        // The path starts here: L_r(p, d) = C(p, d).
        for (int d = first; d < first + count; ++d) pathCost(x, y, d) = cost(x, y, d);
        continue;
      }
      const std::uint16_t* previous = pathCost.at(px, py);
      const int previousCount = windows.count(px, py);
      const int previousMin = *std::min_element(previous, previous + previousCount);
      for (int d = first; d < first + count; ++d) {
        pathCost(x, y, d) = static_cast<std::uint16_t>(pathCostStep(
            cost(x, y, d), previous, windows.first(px, py), previousCount, d, previousMin, P1, P2));
      }
    }
  }
}

}  // namespace

int pathCostStep(int matchingCost, const std::uint16_t* previous, int previousFirst, int previousCount, int d,
                 int previousMin, int P1, int P2) {
  // Eq. 1 with the terms whose disparity lies outside the previous pixel's window absent.
  const auto inPrevious = [&](int k) { return k >= previousFirst && k < previousFirst + previousCount; };
  int best = previousMin + P2;
  if (inPrevious(d)) best = std::min(best, static_cast<int>(previous[d - previousFirst]));
  if (inPrevious(d - 1)) best = std::min(best, previous[d - 1 - previousFirst] + P1);
  if (inPrevious(d + 1)) best = std::min(best, previous[d + 1 - previousFirst] + P1);
  return matchingCost + best - previousMin;
}

void aggregatePaths(const WindowedMatchingCost& cost, int P1, int P2, int paths, WindowedAggregatedCost& sum) {
  WindowedAggregatedCost pathCost;
  pathCost.resize(cost.windows());
  sum.resize(cost.windows());
  std::fill(sum.data(), sum.data() + sum.size(), std::uint16_t{0});
  for (int r = 0; r < paths; ++r) {
    aggregateDirection(cost, kPathDirections[r], P1, P2, pathCost);
    // Eq. 2's sum over paths; bounded by paths * (255 + P2) <= 8 * 4255, which fits 16 bits.
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum.data()[i] = static_cast<std::uint16_t>(sum.data()[i] + pathCost.data()[i]);
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
