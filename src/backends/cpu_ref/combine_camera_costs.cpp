// Triple-SGM camera cost C_S3, reference backend: the rounded mean of the horizontal (C_S) and
// vertical (C_V) census costs.
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined) {
  for (int y = 0; y < horizontal.height(); ++y) {
    for (int x = 0; x < horizontal.width(); ++x) {
      for (int d = 0; d < horizontal.numDisparities(); ++d) {
        // (C_S + C_V) / 2 rounded half up: both in [0, 62], so the mean is too.
        const int c = (horizontal(x, y, d) + vertical(x, y, d) + 1) >> 1;
        combined(x, y, d) = static_cast<std::uint8_t>(c);
      }
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
