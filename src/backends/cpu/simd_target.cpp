// Which instruction set the fast backend's kernels run with on this machine.
#include <hwy/highway.h>
#include <hwy/targets.h>

#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

std::string simdTarget() {
  // Highway dispatches to the best target that is both compiled in and supported at run time.
  const std::int64_t supported = hwy::SupportedTargets() & HWY_TARGETS;
  for (std::int64_t target = 1; target != 0; target <<= 1) {
    if ((supported & target) != 0) return hwy::TargetName(target);  // lower bits are better targets
  }
  return "scalar";
}

}  // namespace lidar_sgm
