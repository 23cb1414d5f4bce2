#pragma once
// Threads for the fast passes after the matcher: the cpu backend's fixed, contiguous ranges
// (core/parallel_ranges.hpp), no result depending on the thread count.

#include "core/parallel_ranges.hpp"

namespace lidar_sgm {
namespace fast {

using lidar_sgm::partBegin;
using lidar_sgm::rangeCount;

/// Runs body(t, begin, end) on rangeCount(count, threads) fixed contiguous ranges of [0, count), in
/// parallel; t is the range's index (for per-range sums added in range order).
template <typename Body>
void parallelRanges(int count, int threads, const Body& body) {
  parallelParts(count, threads, body);
}

}  // namespace fast
}  // namespace lidar_sgm
