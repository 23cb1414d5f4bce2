#pragma once
// lidar_sgm_eval -cloud OUT -reference REF: one cloud held against one reference cloud in 3D
// (lidar_sgm::eval::compareClouds), without running any protocol.

#include <set>
#include <string>

#include "common/arguments.hpp"

namespace lidar_sgm {
namespace apps {

/// The options of this mode (value options; it has no flags).
std::set<std::string> cloudScoreOptions();

/// The help section of this mode.
std::string cloudScoreHelp();

/// Reads both clouds, scores, prints the table and writes OUT_DIR/cloud_distance.json when -out
/// is given. Throws std::invalid_argument / std::runtime_error naming the option or file and the
/// problem (the tool turns them into a message and exit code 1). Returns the exit code.
int runCloudScore(const Arguments& args);

}  // namespace apps
}  // namespace lidar_sgm
