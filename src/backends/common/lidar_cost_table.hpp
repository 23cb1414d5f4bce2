#pragma once
/// @file lidar_cost_table.hpp  The quadratic LiDAR cost of Eq. 4 as an integer lookup table.

#include <cstdint>
#include <cstdlib>
#include <vector>

namespace lidar_sgm {

/// C_L for one point as a function of |d - d_P| in 1/16 px: min(cap, round(64/sigma^2 (d-d_P)^2)).
/// Built once on the host from (sigma, cap) and shared as data by every backend, so that the only
/// floating-point step of the cost happens in one place and all backends agree bit for bit.
class LidarCostTable {
 public:
  LidarCostTable() = default;
  LidarCostTable(float sigma, int cap);

  int cap() const { return cap_; }
  /// Entries for |diff16| = 0 .. size()-1; every larger difference costs cap().
  const std::vector<std::uint8_t>& entries() const { return entries_; }
  std::uint8_t operator()(int diff16) const {
    const auto k = static_cast<std::size_t>(std::abs(diff16));
    return k < entries_.size() ? entries_[k] : static_cast<std::uint8_t>(cap_);
  }

 private:
  int cap_ = 0;
  std::vector<std::uint8_t> entries_;
};

}  // namespace lidar_sgm
