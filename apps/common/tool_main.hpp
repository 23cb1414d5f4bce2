#pragma once
// The one way every tool ends: its work's exit code, or a message and exit code 1 for any error.

#include <cstdio>
#include <exception>

namespace lidar_sgm {
namespace apps {

/// Runs `run(argc, argv)`; an exception becomes "Error: <what>" on stderr and exit code 1, never
/// an abort. The leading newline ends a progress line ("Loading x") the error interrupted.
template <typename Run>
int runTool(Run&& run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nError: %s\n", e.what());
    return 1;
  }
}

}  // namespace apps
}  // namespace lidar_sgm
