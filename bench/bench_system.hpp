#pragma once
// Facts about the machine and the process, for the settings block and the memory lines.

#include <string>

namespace lidar_sgm {
namespace bench {

/// The "model name" of the first CPU in /proc/cpuinfo, or "unknown" (other systems, some ARM).
std::string cpuModel();

/// The process's peak resident set size so far (getrusage ru_maxrss) in MiB; 0 where unknown.
double peakRssMiB();

}  // namespace bench
}  // namespace lidar_sgm
