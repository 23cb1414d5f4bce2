#pragma once
// Threads for the fast passes after the matcher: OpenMP with fixed, contiguous row ranges, the
// rule of the cpu backend (src/backends/cpu/parallel.hpp, private to the core). A range is a
// fixed function of (count, threads) and every output pixel is computed by the same arithmetic
// whichever thread owns it, so no result depends on the thread count. Without OpenMP: one thread.

#include <algorithm>

namespace lidar_sgm {
namespace fast {

/// The t-th of `parts` contiguous ranges of [0, count): [begin, end).
inline int partBegin(int count, int parts, int t) {
  return static_cast<int>(static_cast<long long>(count) * t / parts);
}

/// Runs body(t, begin, end) on min(threads, count) fixed contiguous ranges of [0, count), in
/// parallel; t is the range's index (for per-range sums added in range order).
template <typename Body>
void parallelRanges(int count, int threads, const Body& body) {
  const int parts = std::max(1, std::min(threads, count));
  if (parts == 1) {
    body(0, 0, count);
    return;
  }
#pragma omp parallel for num_threads(parts) schedule(static, 1)
  for (int t = 0; t < parts; ++t) body(t, partBegin(count, parts, t), partBegin(count, parts, t + 1));
}

/// How many ranges parallelRanges(count, threads, ...) makes.
inline int rangeCount(int count, int threads) { return std::max(1, std::min(threads, count)); }

}  // namespace fast
}  // namespace lidar_sgm
