#include "pipeline/fast/depth_table.hpp"

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
  // Binary search over [1, kEntries): the first d16 with depth(d16) <= maxDepth.
  int low = 1;
  int high = kEntries;
  while (low < high) {
    const int middle = low + (high - low) / 2;
    if (depth(middle) <= maxDepth) {
      high = middle;
    } else {
      low = middle + 1;
    }
  }
  return low;
}

}  // namespace fast
}  // namespace lidar_sgm
