#pragma once
// The one way every tool ends: its work's exit code, or a message and exit code 1 for any error.

#include <cstdio>
#include <exception>
#include <new>

namespace lidar_sgm {
namespace apps {

/// Runs `run(argc, argv)`; an exception becomes "Error: <what>" on stderr and exit code 1, never
/// an abort. The leading newline ends a progress line ("Loading x") the error interrupted.
template <typename Run>
int runTool(Run&& run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    // The limits (points per scan, image side) should refuse such inputs first; this is the
    // last guard, so that the message says what happened rather than "std::bad_alloc".
    std::fflush(stdout);
    std::fprintf(stderr, "\nError: out of memory: the inputs and options need more memory than this machine can "
                         "give (std::bad_alloc)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nError: %s\n", e.what());
    return 1;
  }
}

}  // namespace apps
}  // namespace lidar_sgm
