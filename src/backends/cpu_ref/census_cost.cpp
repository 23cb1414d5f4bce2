// Stereo matching cost C_S, reference backend: Hamming distance bit by bit.
#include "lidar_sgm/core/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

int hammingDistance(std::uint64_t a, std::uint64_t b) {
  int distance = 0;
  for (std::uint64_t diff = a ^ b; diff != 0; diff >>= 1) distance += static_cast<int>(diff & 1u);
  return distance;
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
