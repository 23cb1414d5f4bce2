#pragma once
// The allocator of the one-shot tools (lidar_sgm_densify, lidar_sgm_disparity): jemalloc on
// transparent huge pages where the build found it (one_shot_allocator.cpp says why).

#include <string>

namespace lidar_sgm {
namespace apps {

/// What allocates this process's memory, as --version prints it: "jemalloc VERSION, transparent
/// huge pages: MODE" when jemalloc serves malloc, else "the C library's malloc".
std::string allocatorDescription();

}  // namespace apps
}  // namespace lidar_sgm
