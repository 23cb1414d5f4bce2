// Triple-SGM vertical matching cost C_V, reference backend: Hamming distance between the left
// census and the census of the camera above it, along the image column.
#include <bitset>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {
namespace {

int hammingDistance(std::uint64_t a, std::uint64_t b) {
  return static_cast<int>(std::bitset<64>(a ^ b).count());  // number of differing bits
}

}  // namespace

void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost) {
  // The centre-symmetric string has half the bits; doubling keeps both types in [0, 62].
  const int scale = type == CensusType::Census9x7 ? 1 : 2;
  for (int y = 0; y < leftCensus.height; ++y) {
    for (int x = 0; x < leftCensus.width; ++x) {
      for (int d = 0; d < cost.numDisparities(); ++d) {
        // The up camera is above the left one: the scene point appears dv rows lower in it.
        const int yu = y + verticalDisparity(minDisparity + d, ratio16);
        cost(x, y, d) = static_cast<std::uint8_t>(
            yu >= 0 && yu < upCensus.height
                ? scale * hammingDistance(leftCensus(x, y), upCensus(x, yu))
                : kNoCounterpartCensusCost);
      }
    }
  }
}

}  // namespace cpu_ref
}  // namespace lidar_sgm
