#pragma once
/// @file parallel_ranges.hpp  Fixed, contiguous ranges of [0, count) run on OpenMP threads: the rule
/// of the cpu backend's kernels and of the fast passes around the matcher. A range is a fixed
/// function of (count, threads) and every output element is computed by the same arithmetic
/// whichever thread owns it, so no result depends on the thread count. Without OpenMP: one thread.

#include <algorithm>

namespace lidar_sgm {

/// The t-th of `parts` contiguous ranges of [0, count): [begin, end).
inline int partBegin(int count, int parts, int t) {
  return static_cast<int>(static_cast<long long>(count) * t / parts);
}

/// How many ranges parallelParts(count, threads, ...) makes.
inline int rangeCount(int count, int threads) { return std::max(1, std::min(threads, count)); }

/// Runs body(t, begin, end) on rangeCount(count, threads) fixed contiguous ranges of [0, count),
/// in parallel; t is the range's index (per-range scratch or sums; a thread's number would not
/// do inside a caller's own parallel region).
template <typename Body>
void parallelParts(int count, int threads, const Body& body) {
  const int parts = rangeCount(count, threads);
  if (parts == 1) {
    body(0, 0, count);
    return;
  }
#pragma omp parallel for num_threads(parts) schedule(static, 1)
  for (int t = 0; t < parts; ++t) body(t, partBegin(count, parts, t), partBegin(count, parts, t + 1));
}

}  // namespace lidar_sgm
