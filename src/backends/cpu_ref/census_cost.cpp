// Stereo matching cost C_S, reference backend: Hamming distance of census strings.
#include <bitset>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

int hammingDistance(std::uint64_t a, std::uint64_t b) {
  return static_cast<int>(std::bitset<64>(a ^ b).count());  // number of differing bits
}

}  // namespace

void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost) {
  // The centre-symmetric string has half the bits; doubling keeps both types in [0, 62].
  const int scale = type == CensusType::Census9x7 ? 1 : 2;
  for (int y = 0; y < leftCensus.height; ++y) {
    for (int x = 0; x < leftCensus.width; ++x) {
      for (int d = 0; d < cost.numDisparities(); ++d) {
        const int xr = x - (minDisparity + d);
        cost(x, y, d) = static_cast<std::uint8_t>(
            xr >= 0 && xr < rightCensus.width
                ? scale * hammingDistance(leftCensus(x, y), rightCensus(xr, y))
                : kNoCounterpartCensusCost);
      }
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
