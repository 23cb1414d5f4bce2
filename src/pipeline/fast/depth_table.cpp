#include "pipeline/fast/depth_table.hpp"

#include <algorithm>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace fast {

namespace {
constexpr int kEntries = 32768;  // every non-negative int16
}  // namespace

void DepthTable::prepare(double focalBaseline) {
  if (focalBaseline == focalBaseline_ && !depth_.empty()) return;
  depth_.resize(kEntries);
  depth_[0] = 0.0;
  // The specification's expression (geometry::reproject, geometry::depthImage), operand for operand.
  for (int d16 = 1; d16 < kEntries; ++d16) depth_[static_cast<std::size_t>(d16)] = focalBaseline * kDisparityScale / d16;
  focalBaseline_ = focalBaseline;
}

int DepthTable::firstWithin(double maxDepth) const {
  // Over d16 in [1, kEntries) the depths beyond maxDepth come first (z falls as d16 grows).
  const auto first = std::partition_point(depth_.begin() + 1, depth_.end(), [&](double z) { return z > maxDepth; });
  return static_cast<int>(first - depth_.begin());
}

}  // namespace fast
}  // namespace lidar_sgm
