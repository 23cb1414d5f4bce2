// Cost fusion (Eq. 5), reference backend.
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, int alphaWeight256,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused) {
  for (int y = 0; y < stereo.height(); ++y) {
    for (int x = 0; x < stereo.width(); ++x) {
      const bool useStereoOnly = stereoCostWithoutLidar && support(x, y) == 0;
      for (int d = 0; d < stereo.numDisparities(); ++d) {
        const int cL = lidar(x, y, d);
        const int cS = stereo(x, y, d);
        // alpha*C_L + (1-alpha)*C_S with alpha = w/256, rounded to nearest.
        const int c = useStereoOnly ? cS : (alphaWeight256 * cL + (256 - alphaWeight256) * cS + 128) >> 8;
        fused(x, y, d) = static_cast<std::uint8_t>(c);
      }
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
