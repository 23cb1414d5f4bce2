// Built when the fast cpu backend is not (no Highway): there is no SIMD dispatch to report.
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

std::string simdTarget() { return "none"; }

}  // namespace lidar_sgm
