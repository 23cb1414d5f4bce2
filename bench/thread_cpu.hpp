#pragma once
// Timing helpers of the small study programs: the calling thread's CPU time (another process's
// load on the machine does not count) and the median of a few runs.

#include <time.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lidar_sgm {
namespace bench {

inline double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

inline double medianOf(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace bench
}  // namespace lidar_sgm
