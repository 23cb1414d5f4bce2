// What else the winner search reads from one pixel's S (D uint16), for every Highway target: the
// right view's bids (lr_check.cpp) and the peak-ratio margin (confidence_inputs.cpp). Shared so
// that the selection (selection.cpp) can run them on S while it is still in the L1 cache, with
// the very code of the stand-alone stages.
// Per-target header: included once per target, hence the toggled guard instead of #pragma once.
#if defined(LIDAR_SGM_CPU_WINNER_EXTRAS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef LIDAR_SGM_CPU_WINNER_EXTRAS_INL_H_
#undef LIDAR_SGM_CPU_WINNER_EXTRAS_INL_H_
#else
#define LIDAR_SGM_CPU_WINNER_EXTRAS_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {

// The right view's winners of a row, found by letting each left pixel x (in increasing order)
// bid for the right pixels xr = x - minDisparity - d of all its d at once: kept in reverse column
// order, slot offset + (width - 1 - xr), those right pixels are consecutive, so a bid is a vector
// compare-select. `scratch`: rightIndexScratchSize() uint16.
struct RightBids {
  std::uint16_t* bestCost;
  std::uint16_t* bestIndex;
  int offset, width, minDisparity;

  RightBids(std::uint16_t* scratch, int width_, int D, int minDisparity_) : width(width_), minDisparity(minDisparity_) {
    const int N = static_cast<int>(hwy::HWY_NAMESPACE::Lanes(D16()));
    offset = D + std::abs(minDisparity) + N;
    const std::size_t size = rightIndexScratchSize(width, D, minDisparity) / 2;
    bestCost = scratch;
    bestIndex = scratch + size;
    std::fill(bestCost, bestCost + size, std::uint16_t{0xFFFF});    // above every S (<= 8 * 4255)
    std::fill(bestIndex, bestIndex + size, std::uint16_t{0xFFFF});  // -1 as int16: no candidate
  }

  // Left pixel x's bids, S its D costs from disparity index `first` on (a gated pixel's window,
  // gated_stages.hpp: the disparities outside it do not bid).
  HWY_INLINE void bid(const std::uint16_t* HWY_RESTRICT S, int x, int D, int first = 0) {
    namespace hn = hwy::HWY_NAMESPACE;
    const D16 d16;
    const int N = static_cast<int>(hn::Lanes(d16));
    const std::size_t at = base(x, first);
    auto index = hn::Iota(d16, 0);
    for (int i = 0; i < D; i += N) {
      bidVector(hn::LoadU(d16, S + i), at + static_cast<std::size_t>(i), index, first);
      index = hn::Add(index, hn::Set(d16, static_cast<std::uint16_t>(N)));
    }
  }

  // Where left pixel x's bids from disparity index `first` on begin in the scratch: right pixel
  // xr = x - minDisparity - d sits at offset + width - 1 - xr.
  HWY_INLINE std::size_t base(int x, int first) const {
    return static_cast<std::size_t>(offset + width - 1 - x + minDisparity + first);
  }

  // One vector of a left pixel's bids: costs `offer` of window indices `index` (from 0 at the
  // window's start, which is disparity index `first`), at `at` = base(x, first) + the vector's
  // first index.
  HWY_INLINE void bidVector(hwy::HWY_NAMESPACE::Vec<D16> offer, std::size_t at, hwy::HWY_NAMESPACE::Vec<D16> index,
                            int first) {
    namespace hn = hwy::HWY_NAMESPACE;
    const D16 d16;
    const auto cost = hn::LoadU(d16, bestCost + at);
    const auto better = hn::Lt(offer, cost);  // strictly: for a right pixel the smaller d bids first and wins ties
    hn::StoreU(hn::IfThenElse(better, offer, cost), d16, bestCost + at);
    const auto disparity = hn::Add(index, hn::Set(d16, static_cast<std::uint16_t>(first)));
    hn::StoreU(hn::IfThenElse(better, disparity, hn::LoadU(d16, bestIndex + at)), d16, bestIndex + at);
  }

  // After every left pixel of the row has bid.
  void winners(std::int16_t* rightIndex) const {
    for (int xr = 0; xr < width; ++xr) rightIndex[xr] = static_cast<std::int16_t>(bestIndex[offset + width - 1 - xr]);
  }
};

// The peak-ratio margin m from the pixel's second cost S2 (the smallest S more than 1 px from the
// winner; 0xFFFF: none) and its winner's S1 (core/confidence.hpp).
HWY_INLINE void PeakRatioMarginOfSecond(int second, int best, std::uint8_t* margin) {
  if (second == 0xFFFF) {
    *margin = 255;
    return;
  }
  const int value = (256 * (second - best)) / std::max(second, 1);
  *margin = static_cast<std::uint8_t>(std::min(value, 255));
}

// The peak-ratio margin m and S1 of one pixel (core/confidence.hpp) from its S and winner `best`
// (-1: none): a vector minimum over S, the winner's +-1 lanes set to the largest value.
HWY_INLINE void PeakRatioMarginPixel(const std::uint16_t* HWY_RESTRICT S, int D, int best, std::uint8_t* margin,
                                     std::uint16_t* bestCost) {
  namespace hn = hwy::HWY_NAMESPACE;
  if (best < 0) {
    *margin = 0;
    *bestCost = 0;
    return;
  }
  const D16 d16;
  const int N = static_cast<int>(hn::Lanes(d16));  // divides D (a multiple of 16)
  const auto none = hn::Set(d16, std::uint16_t{0xFFFF});  // above every S (<= 8 * 4255)
  *bestCost = S[best];
  // Lanes d with |d - best| <= 1 are left out: d - (best - 1) < 3 as uint16 (d < best - 1 wraps
  // around). One mask per vector and no bounds that depend on the winner: the loop's trip count
  // stays that of the pixel's window, which the branch predictor sees coming.
  const auto below = hn::Set(d16, static_cast<std::uint16_t>(best - 1));
  const auto three = hn::Set(d16, std::uint16_t{3});
  auto index = hn::Iota(d16, 0);
  const auto step = hn::Set(d16, static_cast<std::uint16_t>(N));
  auto lowest = none;
  for (int i = 0; i < D; i += N) {
    const auto own = hn::Lt(hn::Sub(index, below), three);
    lowest = hn::Min(lowest, hn::IfThenElse(own, none, hn::LoadU(d16, S + i)));
    index = hn::Add(index, step);
  }
  PeakRatioMarginOfSecond(static_cast<int>(MinLaneU16(lowest)), S[best], margin);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#endif  // LIDAR_SGM_CPU_WINNER_EXTRAS_INL_H_
