#pragma once
// -h/--help and --version, answered the same way by every tool.

#include <functional>

#include "common/arguments.hpp"

namespace lidar_sgm {
namespace apps {

/// When `args` asks for help, calls `printHelp`; for the version, prints "<tool> <version>"
/// (lidar_sgm::versionString()). Returns true when it answered: the tool then exits 0 without
/// doing any work.
bool answerHelpOrVersion(const Arguments& args, const char* tool, const std::function<void()>& printHelp);

}  // namespace apps
}  // namespace lidar_sgm
