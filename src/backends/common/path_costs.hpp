#pragma once
/// @file path_costs.hpp  How large a path cost L_r of Eq. 1 can get in a frame, which decides
/// whether a backend keeps path costs in 8 bits (as libSGM does): half the memory, and twice
/// the disparities per vector (cpu) or per load (cuda).

#include <algorithm>

#include "backends/common/cost_volume.hpp"
#include "backends/common/stages.hpp"
#include "core/frame_plan.hpp"

namespace lidar_sgm {

/// The largest matching cost C of the frame's mode: the census cost (Eq. 3), the LiDAR cost's cap
/// (Eq. 4), or the larger of the two for the fused cost (Eq. 5 is a weighted mean of them).
inline int largestMatchingCost(const FramePlan& plan) {
  switch (plan.mode) {
    case MatchMode::StereoOnly: return kMaxCensusCost;
    case MatchMode::LidarOnly: return plan.params.lidarCostCap;
    case MatchMode::Fused: break;
  }
  return std::max(kMaxCensusCost, plan.params.lidarCostCap);
}

/// The largest matching cost a stored volume holds (0 when empty): what a stage that is handed a
/// volume, not a frame's plan, bounds its path costs with.
inline int largestMatchingCost(const MatchingCostVolume& cost) {
  return cost.size() == 0 ? 0 : *std::max_element(cost.data(), cost.data() + cost.size());
}

/// The largest path cost: L_r(p, d) = C(p, d) + min(...) - min_k L_r(p - r, k) lies in
/// [0, maxCost + P2], since the min(...) term exceeds the previous minimum by at most P2 (Eq. 1).
constexpr int largestPathCost(int maxCost, int P2) { return maxCost + P2; }

}  // namespace lidar_sgm
