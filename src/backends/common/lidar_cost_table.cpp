#include "backends/common/lidar_cost_table.hpp"

#include <cmath>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

LidarCostTable::LidarCostTable(float sigma, int cap) : cap_(cap) {
  // Eq. 4: 64/sigma^2 * (d - d_P)^2, a Gaussian's negative log-likelihood scaled so that one
  // sigma costs 64 (the paper's constant); capped so it stays in the census cost's range.
  const double scale = 64.0 / (static_cast<double>(sigma) * sigma);
  for (int k = 0;; ++k) {
    const double diff = static_cast<double>(k) / kDisparityScale;
    const long cost = std::lround(scale * diff * diff);
    if (cost >= cap) break;
    entries_.push_back(static_cast<std::uint8_t>(cost));
  }
}

}  // namespace lidar_sgm
