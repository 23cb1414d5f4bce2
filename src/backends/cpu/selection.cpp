// Disparity selection (Eq. 2), fast CPU backend: winner-takes-all vectorised over disparities,
// then cpu_ref's uniqueness rule and parabola, in the same integer arithmetic.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/selection.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <optional>
#include <type_traits>

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


// The first d with the smallest S[d] (ties go to the smaller d, as in cpu_ref).
HWY_INLINE int FirstMinimum(const std::uint16_t* HWY_RESTRICT S, int D) {
  const D16 d16;
  const int N = static_cast<int>(hn::Lanes(d16));
  auto minimum = hn::LoadU(d16, S);
  for (int i = N; i < D; i += N) minimum = hn::Min(minimum, hn::LoadU(d16, S + i));
  const auto target = hn::Set(d16, static_cast<std::uint16_t>(MinLaneU16(minimum)));
  for (int i = 0; i < D; i += N) {
    const intptr_t lane = hn::FindFirstTrue(d16, hn::Eq(hn::LoadU(d16, S + i), target));
    if (lane >= 0) return i + static_cast<int>(lane);
  }
  return 0;  // unreachable: the minimum is one of the lanes
}

// cpu_ref's selection rules for one pixel whose winner is known.
HWY_INLINE void SelectPixel(const std::uint16_t* HWY_RESTRICT S, int best, int x, int D, int minDisparity,
                            int uniquenessRatio, bool subpixel, std::int16_t* disparity16,
                            std::int16_t* bestIndex) {
  bool unique = true;
  if (uniquenessRatio > 0) {
    // OpenCV's rule: every cost farther than 1 px from the winner must exceed it by the ratio.
    for (int d = 0; d < D && unique; ++d) {
      if (std::abs(d - best) > 1 && S[d] * (100 - uniquenessRatio) < S[best] * 100) unique = false;
    }
  }
  if (!unique) {
    disparity16[x] = kInvalidDisparity;
    bestIndex[x] = -1;
    return;
  }
  int offset16 = 0;
  if (subpixel && best > 0 && best < D - 1) {
    // Vertex of the parabola through (best-1, best, best+1), rounded half away from zero.
    const int before = S[best - 1];
    const int after = S[best + 1];
    const int curvature = before + after - 2 * S[best];
    if (curvature > 0) {
      const int numerator = (before - after) * kDisparityScale;
      const int denominator = 2 * curvature;
      const int half = denominator / 2;
      // One division of the magnitude and the sign put back by a select: the sign is the
      // neighbours' order, as likely one way as the other, so a branch on it mispredicts.
      const int magnitude = numerator >= 0 ? numerator : -numerator;
      const int rounded = (magnitude + half) / denominator;
      offset16 = numerator >= 0 ? rounded : -rounded;
    }
  }
  disparity16[x] = static_cast<std::int16_t>((minDisparity + best) * kDisparityScale + offset16);
  bestIndex[x] = static_cast<std::int16_t>(best);
}

void SelectRowImpl(const std::uint16_t* total, int x0, int x1, int D, int minDisparity, int uniquenessRatio,
                   bool subpixel, std::int16_t* disparity16, std::int16_t* bestIndex) {
  for (int x = x0; x < x1; ++x) {
    const std::uint16_t* S = total + static_cast<std::size_t>(x - x0) * D;
    SelectPixel(S, FirstMinimum(S, D), x, D, minDisparity, uniquenessRatio, subpixel, disparity16, bestIndex);
  }
}

// Eq. 2 straight from the paths: per pixel the sum over paths (written to total, which stays in
// the L1 cache for the winner search), its minimum on the fly, then the selection and `extras`.
// With windows (first != nullptr) all of it runs on the pixel's window: S from its first entry,
// the winner's index and the bids shifted back to the whole range (gated_stages.hpp).
// kCount: the number of paths (4 or 8, Parameters::paths), known when compiled, so that the path
// pointers stay in registers and the sum over them is unrolled.
template <int kCount, typename T>
void SumSelectRowT(const T* const* pathList, const std::uint8_t* stored8, const std::uint16_t* stored16,
                   int x0, int x1, int D, int minDisparity, int uniquenessRatio, bool subpixel, std::uint16_t* total,
                   std::int16_t* disparity16, std::int16_t* bestIndex, const WinnerExtras* extras,
                   const std::int16_t* first, const std::int16_t* windowCount) {
  const T* paths[kCount];
  std::copy(pathList, pathList + kCount, paths);
  const D16 d16;
  const int N = static_cast<int>(hn::Lanes(d16));
  const int slot = pathSlot(D);
  const bool margin = extras != nullptr && extras->margin != nullptr;
  const bool pixelTotal = extras != nullptr && extras->pixelTotal;
  std::optional<RightBids> bids;
  if (extras != nullptr && extras->rightIndex != nullptr) {
    bids.emplace(extras->rightScratch, extras->width, D, minDisparity);
  }
  const auto step = hn::Set(d16, static_cast<std::uint16_t>(N));
  const auto none = hn::Set(d16, std::uint16_t{0xFFFF});
  // One pass over the pixel's paths: S, stored for the rules after the winner; its minimum and,
  // per lane, the first index reaching the lane's minimum (strictly smaller replaces), so that the
  // winner needs no second pass and no branch on where it lies; and, with the right view, the
  // pixel's bids while S is in registers.
  //
  // With the margin (and at least 3 lanes), each lane's second smallest S too: the margin's S2 is
  // the smallest S more than 1 px from the winner, and those excluded disparities d - 1, d, d + 1
  // fall in three different lanes, so a lane whose first minimum is one of them offers its second
  // smallest, any other lane its minimum (an equal S elsewhere in the lane is its second smallest).
  // That spares the margin a second pass over S.
  const bool secondInPass = margin && N >= 3;
  struct PixelWinner {
    int best;
    int second;  // S2 when secondInPass
  };
  const auto sumPixel = [&](auto withBids, auto withSecond, int x, int f, int n, std::size_t atPixel,
                            std::size_t inSlot, std::uint16_t* S) {
    auto minimum = none;
    auto second = none;
    auto argument = hn::Zero(d16);
    auto index = hn::Iota(d16, 0);
    const std::size_t bidBase = withBids ? bids->base(x, f) : 0;
    for (int i = 0; i < n; i += N) {
      auto sum = stored8 != nullptr    ? LoadAsU16(stored8 + atPixel + i)
                 : stored16 != nullptr ? hn::LoadU(d16, stored16 + atPixel + i)
                                       : hn::Zero(d16);
      for (int k = 0; k < kCount; ++k) sum = hn::Add(sum, LoadAsU16(paths[k] + inSlot + i));
      hn::StoreU(sum, d16, S + i);
      argument = hn::IfThenElse(hn::Lt(sum, minimum), index, argument);
      if constexpr (decltype(withSecond)::value) second = hn::Min(second, hn::Max(minimum, sum));
      minimum = hn::Min(minimum, sum);
      if constexpr (decltype(withBids)::value) bids->bidVector(sum, bidBase + static_cast<std::size_t>(i), index, f);
      index = hn::Add(index, step);
    }
    // The first d of the smallest S (ties go to the smaller d, as in cpu_ref).
    const auto target = hn::Set(d16, static_cast<std::uint16_t>(MinLaneU16(minimum)));
    PixelWinner winner{static_cast<int>(MinLaneU16(hn::IfThenElse(hn::Eq(minimum, target), argument, none))), 0};
    if constexpr (decltype(withSecond)::value) {
      // Lanes whose first minimum lies within 1 of the winner: d - (best - 1) < 3 as uint16.
      const auto near = hn::Lt(hn::Sub(argument, hn::Set(d16, static_cast<std::uint16_t>(winner.best - 1))),
                               hn::Set(d16, std::uint16_t{3}));
      winner.second = static_cast<int>(MinLaneU16(hn::IfThenElse(near, second, minimum)));
    }
    return winner;
  };
  for (int x = x0; x < x1; ++x) {
    const int f = first == nullptr ? 0 : first[x];
    const int n = first == nullptr ? D : windowCount[x];
    const std::size_t atPixel = static_cast<std::size_t>(x - x0) * D + f;
    const std::size_t inSlot = static_cast<std::size_t>(x) * slot + 1 + f;
    std::uint16_t* S = pixelTotal ? total : total + atPixel;
    const PixelWinner winner =
        bids ? (secondInPass ? sumPixel(std::true_type(), std::true_type(), x, f, n, atPixel, inSlot, S)
                             : sumPixel(std::true_type(), std::false_type(), x, f, n, atPixel, inSlot, S))
             : (secondInPass ? sumPixel(std::false_type(), std::true_type(), x, f, n, atPixel, inSlot, S)
                             : sumPixel(std::false_type(), std::false_type(), x, f, n, atPixel, inSlot, S));
    // On the window: index 0 is disparity index f, so the window's edges are the parabola's.
    SelectPixel(S, winner.best, x, n, minDisparity + f, uniquenessRatio, subpixel, disparity16, bestIndex);
    if (secondInPass) {
      // A winner the uniqueness rule refused has no margin (PeakRatioMarginPixel's rule).
      if (bestIndex[x] < 0) {
        extras->margin[x] = 0;
        extras->bestCost[x] = 0;
      } else {
        extras->bestCost[x] = S[winner.best];
        PeakRatioMarginOfSecond(winner.second, S[winner.best], extras->margin + x);
      }
    } else if (margin) {
      PeakRatioMarginPixel(S, n, bestIndex[x], extras->margin + x, extras->bestCost + x);
    }
    if (bestIndex[x] >= 0) bestIndex[x] = static_cast<std::int16_t>(bestIndex[x] + f);
  }
  if (bids) bids->winners(extras->rightIndex);
}

template <typename T>
void SumSelectRowCount(const T* const* paths, int count, const std::uint8_t* stored8, const std::uint16_t* stored16,
                       int x0, int x1, int D, int minDisparity, int uniquenessRatio, bool subpixel,
                       std::uint16_t* total, std::int16_t* disparity16, std::int16_t* bestIndex,
                       const WinnerExtras* extras, const std::int16_t* first, const std::int16_t* windowCount) {
  if (count != 4 && count != 8) {
    throw std::invalid_argument("sumSelectRow: 4 or 8 paths, not " + std::to_string(count));
  }
  const auto row = count == 8 ? SumSelectRowT<8, T> : SumSelectRowT<4, T>;
  row(paths, stored8, stored16, x0, x1, D, minDisparity, uniquenessRatio, subpixel, total, disparity16, bestIndex,
      extras, first, windowCount);
}

void SumSelectRow8(const std::uint8_t* const* paths, int count, const std::uint8_t* stored8,
                   const std::uint16_t* stored16, int x0, int x1, int D, int minDisparity, int uniquenessRatio,
                   bool subpixel, std::uint16_t* total, std::int16_t* disparity16, std::int16_t* bestIndex,
                   const WinnerExtras* extras, const std::int16_t* first, const std::int16_t* windowCount) {
  SumSelectRowCount(paths, count, stored8, stored16, x0, x1, D, minDisparity, uniquenessRatio, subpixel, total,
                    disparity16, bestIndex, extras, first, windowCount);
}
void SumSelectRow16(const std::uint16_t* const* paths, int count, const std::uint8_t* stored8,
                    const std::uint16_t* stored16, int x0, int x1, int D, int minDisparity, int uniquenessRatio,
                    bool subpixel, std::uint16_t* total, std::int16_t* disparity16, std::int16_t* bestIndex,
                   const WinnerExtras* extras, const std::int16_t* first, const std::int16_t* windowCount) {
  SumSelectRowCount(paths, count, stored8, stored16, x0, x1, D, minDisparity, uniquenessRatio, subpixel, total,
                    disparity16, bestIndex, extras, first, windowCount);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(SelectRowImpl);
HWY_EXPORT(SumSelectRow8);
HWY_EXPORT(SumSelectRow16);

void selectRow(const std::uint16_t* total, int x0, int x1, int numDisparities, int minDisparity,
               int uniquenessRatio, bool subpixel, std::int16_t* disparity16, std::int16_t* bestIndex) {
  HWY_DYNAMIC_DISPATCH(SelectRowImpl)(total, x0, x1, numDisparities, minDisparity, uniquenessRatio, subpixel,
                                      disparity16, bestIndex);
}

void sumSelectRow(const std::uint8_t* const* paths, int count, const std::uint8_t* stored8,
                  const std::uint16_t* stored16, int x0, int x1, int numDisparities, int minDisparity,
                  int uniquenessRatio, bool subpixel, std::uint16_t* total, std::int16_t* disparity16,
                  std::int16_t* bestIndex, const WinnerExtras* extras, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(SumSelectRow8)(paths, count, stored8, stored16, x0, x1, numDisparities, minDisparity,
                                      uniquenessRatio, subpixel, total, disparity16, bestIndex, extras, windows.first,
                                      windows.count);
}
void sumSelectRow(const std::uint16_t* const* paths, int count, const std::uint8_t* stored8,
                  const std::uint16_t* stored16, int x0, int x1, int numDisparities, int minDisparity,
                  int uniquenessRatio, bool subpixel, std::uint16_t* total, std::int16_t* disparity16,
                  std::int16_t* bestIndex, const WinnerExtras* extras, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(SumSelectRow16)(paths, count, stored8, stored16, x0, x1, numDisparities, minDisparity,
                                       uniquenessRatio, subpixel, total, disparity16, bestIndex, extras, windows.first,
                                       windows.count);
}

void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out, int threads) {
  parallelRanges(sum.height(), threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      selectRow(sum.at(0, y), 0, sum.width(), sum.numDisparities(), minDisparity, uniquenessRatio, subpixel,
                out.disparity16.row(y), out.bestIndex.row(y));
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
