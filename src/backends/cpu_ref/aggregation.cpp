// SGM cost aggregation (Eq. 1), reference backend: one full path-cost volume per direction.
#include <algorithm>
#include <vector>

#include "backends/common/stages.hpp"
#include "backends/common/path_directions.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

// L_r for every pixel along direction r, in the order that visits p - r before p.
void aggregateDirection(const MatchingCostVolume& cost, PathDirection r, int P1, int P2,
                        AggregatedCostVolume& pathCost) {
  const int width = cost.width();
  const int height = cost.height();
  const int D = cost.numDisparities();
  for (int i = 0; i < height; ++i) {
    const int y = r.dy >= 0 ? i : height - 1 - i;
    for (int j = 0; j < width; ++j) {
      const int x = r.dx >= 0 ? j : width - 1 - j;
      const int px = x - r.dx;
      const int py = y - r.dy;
      std::uint16_t* L = pathCost.at(x, y);
      if (px < 0 || px >= width || py < 0 || py >= height) {
        // The path starts here: L_r(p, d) = C(p, d).
        for (int d = 0; d < D; ++d) L[d] = cost(x, y, d);
        continue;
      }
      const std::uint16_t* previous = pathCost.at(px, py);
      const int previousMin = *std::min_element(previous, previous + D);
      for (int d = 0; d < D; ++d) {
        L[d] = static_cast<std::uint16_t>(pathCostStep(cost(x, y, d), previous, D, d, previousMin, P1, P2));
      }
    }
  }
}

}  // namespace

int pathCostStep(int matchingCost, const std::uint16_t* previous, int numDisparities, int d,
                 int previousMin, int P1, int P2) {
  // Eq. 1: C(p,d) + min(L(p-r,d), L(p-r,d-1)+P1, L(p-r,d+1)+P1, min_i L(p-r,i)+P2) - min_k L(p-r,k).
  int best = previous[d];
  if (d > 0) best = std::min(best, previous[d - 1] + P1);
  if (d + 1 < numDisparities) best = std::min(best, previous[d + 1] + P1);
  best = std::min(best, previousMin + P2);
  return matchingCost + best - previousMin;
}

void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths,
                    AggregatedCostVolume& sum) {
  AggregatedCostVolume pathCost(cost.width(), cost.height(), cost.numDisparities());
  sum.resize(cost.width(), cost.height(), cost.numDisparities());
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
