#pragma once
// Threads for the fast CPU backend: OpenMP, with fixed, contiguous partitions.
//
// Why OpenMP: it ships with every compiler we target (libgomp/libomp, no extra package), its
// `parallel` + `barrier` is the cheapest way to keep a small team in lock step row by row (the
// SGM sweeps synchronise twice per image row), and `num_threads` maps one to one onto
// Parameters::threads. Partitions are fixed functions of (count, threads), and every output
// element is computed by exactly the same arithmetic whichever thread owns it, so the result
// never depends on the number of threads. Without OpenMP the backend runs on one thread.

#include "core/parallel_ranges.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace lidar_sgm {
namespace cpu {

using lidar_sgm::parallelParts;
using lidar_sgm::partBegin;
using lidar_sgm::rangeCount;

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
