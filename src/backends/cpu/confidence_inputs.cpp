// The backend's part of the confidence (core/confidence.hpp), fast CPU backend: the peak-ratio
// margin is a masked vector minimum over the pixel's S (the winner's +-1 lanes set to the
// largest value), the left-right difference a few reads per pixel; rows split among threads.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/confidence_inputs.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

#include "backends/cpu/simd-inl.h"
#include "backends/cpu/winner_extras-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void PeakRatioMarginRowImpl(const std::uint16_t* totalRow, int width, int D, const std::int16_t* bestIndex,
                            std::uint8_t* margin, std::uint16_t* bestCost) {
  for (int x = 0; x < width; ++x) {
    PeakRatioMarginPixel(totalRow + static_cast<std::size_t>(x) * D, D, bestIndex[x], margin + x, bestCost + x);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(PeakRatioMarginRowImpl);

void peakRatioMarginRow(const std::uint16_t* totalRow, int width, int numDisparities, const std::int16_t* bestIndex,
                        std::uint8_t* margin, std::uint16_t* bestCost) {
  HWY_DYNAMIC_DISPATCH(PeakRatioMarginRowImpl)(totalRow, width, numDisparities, bestIndex, margin, bestCost);
}

void leftRightDifferenceRow(const std::int16_t* bestIndex, const std::int16_t* rightIndex, int width,
                            int minDisparity, std::uint8_t* difference) {
  for (int x = 0; x < width; ++x) {
    const int best = bestIndex[x];
    const int xr = x - (minDisparity + best);
    if (best < 0 || xr < 0 || xr >= width || rightIndex[xr] < 0) {
      difference[x] = kNoCounterpartDifference;
    } else {
      difference[x] = static_cast<std::uint8_t>(std::min(std::abs(rightIndex[xr] - best), 254));
    }
  }
}

void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost, int threads) {
  parallelRanges(sum.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      peakRatioMarginRow(sum.at(0, y), sum.width(), sum.numDisparities(), bestIndex.row(y), margin.row(y),
                         bestCost.row(y));
    }
  });
}

void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference, int threads) {
  parallelRanges(bestIndex.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      leftRightDifferenceRow(bestIndex.row(y), rightIndex.row(y), bestIndex.width, minDisparity, difference.row(y));
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
