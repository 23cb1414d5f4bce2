// Triple-SGM camera cost C_S3 = (C_S + C_V + 1) >> 1, fast CPU backend: the rounded mean is
// exactly the unsigned byte average (pavgb / urhadd) every SIMD instruction set has.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/combine_camera_costs.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void CombineCameraCostRowImpl(const std::uint8_t* horizontal, const std::uint8_t* vertical, std::size_t n,
                              std::uint8_t* combined) {
  const hn::ScalableTag<std::uint8_t> d8;
  const std::size_t N = hn::Lanes(d8);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    hn::StoreU(hn::AverageRound(hn::LoadU(d8, horizontal + i), hn::LoadU(d8, vertical + i)), d8, combined + i);
  }
  for (; i < n; ++i) combined[i] = static_cast<std::uint8_t>((horizontal[i] + vertical[i] + 1) >> 1);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(CombineCameraCostRowImpl);

void combineCameraCostRow(const std::uint8_t* horizontal, const std::uint8_t* vertical, std::size_t n,
                          std::uint8_t* combined) {
  HWY_DYNAMIC_DISPATCH(CombineCameraCostRowImpl)(horizontal, vertical, n, combined);
}

void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined, int threads) {
  const auto rowSize = static_cast<std::size_t>(horizontal.width()) * horizontal.numDisparities();
  parallelRanges(horizontal.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) combineCameraCostRow(horizontal.at(0, y), vertical.at(0, y), rowSize, combined.at(0, y));
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
