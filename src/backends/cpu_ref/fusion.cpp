// Cost fusion (Eq. 5), reference backend.
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, ImageView<const std::uint16_t> weights,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused) {
  for (int y = 0; y < stereo.height(); ++y) {
    for (int x = 0; x < stereo.width(); ++x) {
      const bool useStereoOnly = stereoCostWithoutLidar && support(x, y) == 0;
      const int w = weights(x, y);
      for (int d = 0; d < stereo.numDisparities(); ++d) {
        const int cL = lidar(x, y, d);
        const int cS = stereo(x, y, d);
        // alpha*C_L + (1-alpha)*C_S with alpha = w/256, rounded to nearest.
        const int c = useStereoOnly ? cS : (w * cL + (256 - w) * cS + 128) >> 8;
        fused(x, y, d) = static_cast<std::uint8_t>(c);
      }
    }
  }
}

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, int alphaWeight256,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused) {
  const Image<std::uint16_t> weights(stereo.width(), stereo.height(), static_cast<std::uint16_t>(alphaWeight256));
  fuseCosts(lidar, stereo, support, weights.view(), stereoCostWithoutLidar, fused);
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
