// Cost fusion (Eq. 5), fast CPU backend: alpha * C_L + (1 - alpha) * C_S in 16-bit lanes, with
// cpu_ref's weights out of 256 and rounding (simd-inl.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/fusion.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstring>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

#include "backends/cpu/simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {

void FuseCostRowImpl(const std::uint8_t* lidar, const std::uint8_t* stereo, std::size_t n, int alphaWeight256,
                     std::uint8_t* fused) {
  FuseBytes(lidar, stereo, n, alphaWeight256, fused);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(FuseCostRowImpl);

void fuseCostRow(const std::uint8_t* lidar, const std::uint8_t* stereo, std::size_t n, int alphaWeight256,
                 std::uint8_t* fused) {
  HWY_DYNAMIC_DISPATCH(FuseCostRowImpl)(lidar, stereo, n, alphaWeight256, fused);
}

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, int alphaWeight256, bool stereoCostWithoutLidar,
               MatchingCostVolume& fused, int threads) {
  const int width = stereo.width();
  const auto D = static_cast<std::size_t>(stereo.numDisparities());
  parallelRanges(stereo.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      fuseCostRow(lidar.at(0, y), stereo.at(0, y), D * width, alphaWeight256, fused.at(0, y));
      if (!stereoCostWithoutLidar) continue;
      // Where no LiDAR point touches the pixel the LiDAR knows nothing: keep C_S.
      for (int x = 0; x < width; ++x) {
        if (support(x, y) == 0) std::memcpy(fused.at(x, y), stereo.at(x, y), D);
      }
    }
  });
}

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, ImageView<const std::uint16_t> weights,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused, int threads) {
  const int width = stereo.width();
  const auto D = static_cast<std::size_t>(stereo.numDisparities());
  parallelRanges(stereo.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      // One weight per pixel: the row kernel runs over the pixel's D costs.
      for (int x = 0; x < width; ++x) {
        if (stereoCostWithoutLidar && support(x, y) == 0) {
          std::memcpy(fused.at(x, y), stereo.at(x, y), D);
        } else {
          fuseCostRow(lidar.at(x, y), stereo.at(x, y), D, weights(x, y), fused.at(x, y));
        }
      }
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
