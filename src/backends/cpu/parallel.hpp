#pragma once
// Threads for the fast CPU backend: OpenMP, with fixed, contiguous partitions.
//
// Why OpenMP: it ships with every compiler we target (libgomp/libomp, no extra package), its
// `parallel` + `barrier` is the cheapest way to keep a small team in lock step row by row (the
// SGM sweeps synchronise twice per image row), and `num_threads` maps one to one onto
// Parameters::threads. Partitions are fixed functions of (count, threads), and every output
// element is computed by exactly the same arithmetic whichever thread owns it, so the result
// never depends on the number of threads. Without OpenMP the backend runs on one thread.

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace lidar_sgm {
namespace cpu {

/// The t-th of `parts` contiguous ranges of [0, count): [begin, end).
inline int partBegin(int count, int parts, int t) {
  return static_cast<int>(static_cast<long long>(count) * t / parts);
}

/// How many ranges parallelRanges splits [0, count) into for `threads`.
inline int rangeCount(int count, int threads) { return std::max(1, std::min(threads, count)); }
/// Runs body(part, begin, end) on rangeCount(count, threads) fixed contiguous ranges of [0, count),
/// in parallel; `part` numbers the range (for per-range scratch: a thread's number would not, in a
/// caller's own parallel region).
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
/// Runs body(begin, end) on `threads` fixed contiguous ranges of [0, count), in parallel.
template <typename Body>
void parallelRanges(int count, int threads, const Body& body) {
  parallelParts(count, threads, [&](int, int begin, int end) { body(begin, end); });
}

inline int threadIndex() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Inside a parallel region: the team it really got (OpenMP may give fewer threads than asked
/// for, e.g. one when the caller is itself inside a parallel region); 1 without OpenMP.
inline int teamSize() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

}  // namespace cpu
}  // namespace lidar_sgm
