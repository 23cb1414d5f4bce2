#include "common/help_version.hpp"

#include <cstdio>

#include "lidar_sgm/version.hpp"

namespace lidar_sgm {
namespace apps {

bool answerHelpOrVersion(const Arguments& args, const char* tool, const std::function<void()>& printHelp) {
  if (args.helpRequested()) {
    printHelp();
    return true;
  }
  if (args.versionRequested()) {
    std::printf("%s %s\n", tool, versionString());
    return true;
  }
  return false;
}

}  // namespace apps
}  // namespace lidar_sgm
