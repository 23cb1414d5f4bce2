#pragma once
// Where the third-party evaluation data lives (../shared/data beside the repository).

#include <cstdlib>
#include <filesystem>
#include <string>

#include "common/test_paths.hpp"

namespace lidar_sgm {
namespace test {

/// $LIDAR_SGM_DATA, else the ../shared/data found at configure time.
inline std::string sharedDataRoot() {
  if (const char* env = std::getenv("LIDAR_SGM_DATA")) return env;
  return kSharedDataDir;
}

inline bool haveSharedData(const std::string& folder) {
  return std::filesystem::is_directory(sharedDataRoot() + "/" + folder);
}

}  // namespace test
}  // namespace lidar_sgm
