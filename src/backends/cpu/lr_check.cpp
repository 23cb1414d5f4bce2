// Left-right consistency check, fast CPU backend. The right view's winners (read diagonally from
// the left volume, as OpenCV's SGBM does) are found by scanning the left pixels in order and
// letting each one bid for the right pixels x - minDisparity - d of all its d at once: kept in
// reverse column order those right pixels are consecutive, so a bid is a vector compare-select.
// The check itself reads a handful of values per pixel, rows split among threads.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/lr_check.cpp"
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


void RightDisparityIndexRowImpl(const std::uint16_t* totalRow, int width, int D, int minDisparity,
                                std::uint16_t* scratch, std::int16_t* rightIndex) {
  RightBids bids(scratch, width, D, minDisparity);
  for (int x = 0; x < width; ++x) bids.bid(totalRow + static_cast<std::size_t>(x) * D, x, D);
  bids.winners(rightIndex);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(RightDisparityIndexRowImpl);

std::size_t rightIndexScratchSize(int width, int numDisparities, int minDisparity) {
  const std::size_t slots = static_cast<std::size_t>(width) + 2 * static_cast<std::size_t>(numDisparities) +
                            2 * static_cast<std::size_t>(std::abs(minDisparity)) + 64;
  return 2 * slots;
}

void rightDisparityIndexRow(const std::uint16_t* totalRow, int width, int numDisparities, int minDisparity,
                            std::uint16_t* scratch, std::int16_t* rightIndex) {
  HWY_DYNAMIC_DISPATCH(RightDisparityIndexRowImpl)(totalRow, width, numDisparities, minDisparity, scratch,
                                                   rightIndex);
}

void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity, ImageView<std::int16_t> rightIndex,
                         int threads) {
  parallelRanges(sum.height(), threads, [&](int y0, int y1) {
    std::vector<std::uint16_t> scratch(rightIndexScratchSize(sum.width(), sum.numDisparities(), minDisparity));
    for (int y = y0; y < y1; ++y) {
      rightDisparityIndexRow(sum.at(0, y), sum.width(), sum.numDisparities(), minDisparity, scratch.data(),
                             rightIndex.row(y));
    }
  });
}

void leftRightCheckRow(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                       ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                       bool keepNoCounterpart, int y) {
  const int width = rightIndex.width;
  std::int16_t* best = disparity.bestIndex.row(y);
  std::int16_t* value = disparity.disparity16.row(y);
  const std::int16_t* right = rightIndex.row(y);
  const std::uint8_t* covered = support.empty() ? nullptr : support.row(y);
  for (int x = 0; x < width; ++x) {
    if (best[x] < 0) continue;
    bool keep = true;
    const int xr = x - (minDisparity + best[x]);
    if (xr < 0 || xr >= width) {
      keep = keepNoCounterpart;  // the right camera cannot see it: nothing to compare
    } else if (covered != nullptr && covered[x] != 0) {
      keep = true;  // a LiDAR point measured it
    } else {
      keep = right[xr] >= 0 && std::abs(right[xr] - best[x]) <= disp12MaxDiff;
    }
    if (!keep) {
      value[x] = kInvalidDisparity;
      best[x] = -1;
    }
  }
}

void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                    bool keepNoCounterpart, int threads) {
  parallelRanges(rightIndex.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      leftRightCheckRow(disparity, rightIndex, support, minDisparity, disp12MaxDiff, keepNoCounterpart, y);
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
