// Triple-SGM vertical matching cost C_V, fast CPU backend: Hamming distances along the column,
// with the CPU's population count (compiled per instruction set).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/vertical_census_cost.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {

void VerticalCensusCostRowImpl(const std::uint64_t* leftRow, ImageView<const std::uint64_t> upCensus, int y, int x0,
                               int x1, int ratio16, int minDisparity, int D, int scale, std::uint8_t* cost) {
  for (int x = x0; x < x1; ++x) {
    std::uint8_t* c = cost + static_cast<std::size_t>(x - x0) * D;
    const std::uint64_t left = leftRow[x];
    for (int d = 0; d < D; ++d) {
      // The up camera is above the left one: the scene point appears dv rows lower in it.
      const int yu = y + verticalDisparity(minDisparity + d, ratio16);
      c[d] = static_cast<std::uint8_t>(yu >= 0 && yu < upCensus.height
                                           ? scale * __builtin_popcountll(left ^ upCensus(x, yu))
                                           : kNoCounterpartCensusCost);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(VerticalCensusCostRowImpl);

void verticalCensusCostRow(const std::uint64_t* leftRow, ImageView<const std::uint64_t> upCensus, int y, int x0,
                           int x1, int ratio16, int minDisparity, int numDisparities, int scale, std::uint8_t* cost) {
  HWY_DYNAMIC_DISPATCH(VerticalCensusCostRowImpl)(leftRow, upCensus, y, x0, x1, ratio16, minDisparity,
                                                  numDisparities, scale, cost);
}

void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost, int threads) {
  const int scale = type == CensusType::Census9x7 ? 1 : 2;
  parallelRanges(leftCensus.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      verticalCensusCostRow(leftCensus.row(y), upCensus, y, 0, leftCensus.width, ratio16, minDisparity,
                            cost.numDisparities(), scale, cost.at(0, y));
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
