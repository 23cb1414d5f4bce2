// SGM cost aggregation (Eq. 1), fast CPU backend: the path recursion vectorised over
// disparities, and the whole-volume aggregatePaths stage built from it.
//
// Path costs are kept in 8 bits whenever they provably fit: L_r(p, d) = C(p, d) + min(...) -
// min_k L_r(p - r, k) lies in [0, maxCost + P2] (the min(...) term exceeds the previous minimum
// by at most P2), which is 162 with the paper's costs and penalties. 8-bit lanes do twice the
// disparities per instruction and halve the row buffers. The +P1 and +P2 candidates saturate,
// which cannot change the minimum: L(p - r, d) itself is at most maxCost + P2 < 255. Otherwise
// (large P2 or LiDAR cap) 16 bits, where nothing can overflow: L <= 255 + 4000, + P2 <= 8255.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/aggregation.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

#include "backends/common/path_costs.hpp"
#include "backends/common/path_directions.hpp"
#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

#include "backends/cpu/simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Vector tags of a path element type: whole vectors of up to 32 bytes, and a 16-lane tail
// (D is a multiple of 16, not always of 32).
template <typename T>
struct PathTags {
  using Full = hn::CappedTag<T, 32 / sizeof(T)>;
  using Tail = hn::CappedTag<T, 16>;
};

template <class DT>
HWY_INLINE hn::Vec<DT> LoadCost(DT d, const std::uint8_t* HWY_RESTRICT cost) {
  if constexpr (sizeof(hn::TFromD<DT>) == 1) {
    return hn::LoadU(d, cost);
  } else {
    return hn::PromoteTo(d, hn::LoadU(hn::Rebind<std::uint8_t, DT>(), cost));
  }
}

// The smallest lane. Highway 1.0 has no 8-bit MinOfLanes: reduce byte pairs as 16-bit lanes.
template <class DT>
HWY_INLINE unsigned MinLane(DT d, hn::Vec<DT> v) {
  if constexpr (sizeof(hn::TFromD<DT>) == 1 && HWY_TARGET != HWY_SCALAR) {  // scalar: one lane
    const hn::Repartition<std::uint16_t, DT> d16;
    const auto pairs = hn::BitCast(d16, v);
    const auto m = hn::Min(hn::And(pairs, hn::Set(d16, std::uint16_t{0xFF})), hn::ShiftRight<8>(pairs));
    return hn::GetLane(hn::MinOfLanes(d16, m));
  } else if constexpr (sizeof(hn::TFromD<DT>) == 1) {
    (void)d;
    return hn::GetLane(v);
  } else {
    return hn::GetLane(hn::MinOfLanes(d, v));
  }
}

// Eq. 1 for the Lanes(d) disparities from i; accumulates min_d L into `minimum`.
template <class DT, typename T = hn::TFromD<DT>>
HWY_INLINE void StepBlock(DT d, int i, const std::uint8_t* HWY_RESTRICT cost, const T* HWY_RESTRICT prev,
                          T* HWY_RESTRICT out, T P1, T jump, T prevMin, hn::Vec<DT>& minimum) {
  const auto same = hn::LoadU(d, prev + i);
  const auto below = hn::SaturatedAdd(hn::LoadU(d, prev + i - 1), hn::Set(d, P1));
  const auto above = hn::SaturatedAdd(hn::LoadU(d, prev + i + 1), hn::Set(d, P1));
  const auto best = hn::Min(hn::Min(same, below), hn::Min(above, hn::Set(d, jump)));
  const auto L = hn::Add(hn::Sub(best, hn::Set(d, prevMin)), LoadCost(d, cost + i));
  hn::StoreU(L, d, out + i);
  minimum = hn::Min(minimum, L);
}

// One step of Eq. 1 for every d: out[d] = C(d) + min(prev[d], prev[d-1] + P1, prev[d+1] + P1,
// prevMin + P2) - prevMin. `prev` and `out` point at d = 0 of a slot (sentinels at -1 and D).
// Returns min_d out[d]. Blocks of the widest vector first (64 bytes where the target has them),
// then narrower ones (D is a multiple of 16 lanes); the running minimum narrows with the blocks,
// so one reduction of a 16-byte or 32-byte vector ends the step (on a horizontal path it is on the
// chain from one pixel to the next).
template <typename T>
HWY_INLINE unsigned PathStep(const std::uint8_t* HWY_RESTRICT cost, const T* HWY_RESTRICT prev, unsigned prevMin,
                             T* HWY_RESTRICT out, int D, int P1, int P2) {
  const typename PathTags<T>::Full df;
  const typename PathTags<T>::Tail dt;
  constexpr unsigned kMax = std::numeric_limits<T>::max();
  const T jump = static_cast<T>(std::min(prevMin + static_cast<unsigned>(P2), kMax));
  const T p1 = static_cast<T>(std::min(static_cast<unsigned>(P1), kMax));
  const T minPrev = static_cast<T>(prevMin);
  const int N = static_cast<int>(hn::Lanes(df));
  int i = 0;
#if HWY_MAX_BYTES >= 64
  const hn::Twice<decltype(df)> dw;
  const int NW = static_cast<int>(hn::Lanes(dw));
  auto wide = hn::Set(dw, static_cast<T>(kMax));
  for (; i + NW <= D; i += NW) StepBlock(dw, i, cost, prev, out, p1, jump, minPrev, wide);
  auto minimum = MinOfHalves(dw, wide);
#else
  auto minimum = hn::Set(df, static_cast<T>(kMax));
#endif
  for (; i + N <= D; i += N) StepBlock(df, i, cost, prev, out, p1, jump, minPrev, minimum);
#if HWY_MAX_BYTES >= 32
  if constexpr (sizeof(T) == 1) {
    // 8-bit lanes: the 16-lane tail is half a full vector.
    auto tail = MinOfHalves(df, minimum);
    for (; i < D; i += static_cast<int>(hn::Lanes(dt))) StepBlock(dt, i, cost, prev, out, p1, jump, minPrev, tail);
    return MinLane(dt, tail);
  } else
#endif
  {
    unsigned result = MinLane(df, minimum);
    if (i < D) {
      auto tail = hn::Set(dt, static_cast<T>(kMax));
      for (; i < D; i += static_cast<int>(hn::Lanes(dt))) StepBlock(dt, i, cost, prev, out, p1, jump, minPrev, tail);
      result = std::min(result, MinLane(dt, tail));
    }
    return result;
  }
}

// The start of a path: L = C (Eq. 1 with no previous pixel).
template <typename T>
HWY_INLINE unsigned PathStart(const std::uint8_t* HWY_RESTRICT cost, T* HWY_RESTRICT out, int D) {
  unsigned minimum = std::numeric_limits<T>::max();
  for (int d = 0; d < D; ++d) {
    out[d] = cost[d];
    minimum = std::min<unsigned>(minimum, cost[d]);
  }
  return minimum;
}

// The first disparity index and the number of disparities pixel x searches (the whole range
// without windows). A gated pixel's slot holds the sentinel outside its window: the next pixel on
// the path must read the entries outside this pixel's window as absent (gated_stages.hpp).
template <typename T>
HWY_INLINE T* WindowOfSlot(T* slotValues, const std::int16_t* first, const std::int16_t* count, int x, int D,
                           int& windowFirst, int& windowCount) {
  windowFirst = first == nullptr ? 0 : first[x];
  windowCount = first == nullptr ? D : count[x];
  if (windowCount < D) {
    // The whole slot in whole vectors (D is a multiple of 16), then the step overwrites the
    // window: a few stores of fixed width instead of two fills of a length known only now.
    const typename PathTags<T>::Full df;
    const typename PathTags<T>::Tail dt;
    const int N = static_cast<int>(hn::Lanes(df));
    int i = 0;
    for (; i + N <= D; i += N) hn::StoreU(hn::Set(df, pathSentinel<T>()), df, slotValues + i);
    for (; i < D; i += static_cast<int>(hn::Lanes(dt))) hn::StoreU(hn::Set(dt, pathSentinel<T>()), dt, slotValues + i);
  }
  return slotValues + windowFirst;
}

template <typename T>
void PathRowFromPreviousT(const std::uint8_t* costRow, int costX0, const T* previous, const std::uint16_t* previousMin,
                          int dx, int width, int x0, int x1, int D, int P1, int P2, T* out, std::uint16_t* outMin,
                          const std::int16_t* first, const std::int16_t* count, const std::uint32_t* costOffset) {
  const int slot = pathSlot(D);
  for (int x = x0; x < x1; ++x) {
    int f = 0;
    int n = D;
    T* L = WindowOfSlot(out + static_cast<std::size_t>(x) * slot + 1, first, count, x, D, f, n);
    const std::uint8_t* c = costOffset != nullptr ? costRow + costOffset[x]
                                                  : costRow + static_cast<std::size_t>(x - costX0) * D + f;
    const int px = x - dx;
    if (previous == nullptr || px < 0 || px >= width) {
      outMin[x] = static_cast<std::uint16_t>(PathStart(c, L, n));
    } else {
      // The previous slot from the same disparity on: its entries outside its own window are
      // sentinels, and its ends (slot[0], slot[D + 1]) too.
      outMin[x] = static_cast<std::uint16_t>(
          PathStep(c, previous + static_cast<std::size_t>(px) * slot + 1 + f, previousMin[px], L, n, P1, P2));
    }
  }
}

template <typename T>
void PathRowHorizontalT(const std::uint8_t* costRow, int dx, int width, int D, int P1, int P2, T* out) {
  const int slot = pathSlot(D);
  const int first = dx > 0 ? 0 : width - 1;
  unsigned minimum = PathStart(costRow + static_cast<std::size_t>(first) * D, out + static_cast<std::size_t>(first) * slot + 1, D);
  for (int j = 1; j < width; ++j) {
    const int x = dx > 0 ? j : width - 1 - j;
    minimum = PathStep(costRow + static_cast<std::size_t>(x) * D, out + static_cast<std::size_t>(x - dx) * slot + 1,
                       minimum, out + static_cast<std::size_t>(x) * slot + 1, D, P1, P2);
  }
}

// Both horizontal paths of a row at once: left to right at x = j and right to left at
// x = width - 1 - j. Each walk is one long dependency chain (a pixel needs its predecessor's
// minimum); interleaving two independent chains keeps the vector units busy.
template <typename T>
void PathRowsHorizontalT(const std::uint8_t* costRow, int width, int D, int P1, int P2, T* rightward, T* leftward,
                         const std::int16_t* first, const std::int16_t* count, const std::uint32_t* costOffset) {
  const int slot = pathSlot(D);
  const auto at = [&](T* row, int x) { return row + static_cast<std::size_t>(x) * slot + 1; };
  // Pixel x's window's costs (its first entry is disparity index f).
  const auto cost = [&](int x, int f) {
    return costOffset != nullptr ? costRow + costOffset[x] : costRow + static_cast<std::size_t>(x) * D + f;
  };
  int f = 0;
  int n = D;
  T* L = WindowOfSlot(at(rightward, 0), first, count, 0, D, f, n);
  unsigned minRight = PathStart(cost(0, f), L, n);
  L = WindowOfSlot(at(leftward, width - 1), first, count, width - 1, D, f, n);
  unsigned minLeft = PathStart(cost(width - 1, f), L, n);
  for (int j = 1; j < width; ++j) {
    const int xr = j;
    const int xl = width - 1 - j;
    L = WindowOfSlot(at(rightward, xr), first, count, xr, D, f, n);
    minRight = PathStep(cost(xr, f), at(rightward, xr - 1) + f, minRight, L, n, P1, P2);
    L = WindowOfSlot(at(leftward, xl), first, count, xl, D, f, n);
    minLeft = PathStep(cost(xl, f), at(leftward, xl + 1) + f, minLeft, L, n, P1, P2);
  }
}

template <typename T>
void StorePathSumT(const T* const* paths, int count, int x0, int x1, int D, std::uint8_t* stored8,
                   std::uint16_t* stored16) {
  const D16 d16;
  const hn::Rebind<std::uint8_t, D16> d8;
  const int N = static_cast<int>(hn::Lanes(d16));
  const int slot = pathSlot(D);
  for (int x = x0; x < x1; ++x) {
    const std::size_t local = static_cast<std::size_t>(x - x0) * D;
    const std::size_t inSlot = static_cast<std::size_t>(x) * slot + 1;
    for (int i = 0; i < D; i += N) {
      auto sum = LoadAsU16(paths[0] + inSlot + i);
      for (int k = 1; k < count; ++k) sum = hn::Add(sum, LoadAsU16(paths[k] + inSlot + i));
      if (stored8 != nullptr) {
        hn::StoreU(hn::DemoteTo(d8, hn::BitCast(hn::Rebind<std::int16_t, D16>(), sum)), d8, stored8 + local + i);
      } else {
        hn::StoreU(sum, d16, stored16 + local + i);
      }
    }
  }
}

template <typename T>
void AddPathRowT(const T* path, int x0, int x1, int D, std::uint16_t* sumRow) {
  const D16 d16;
  const int N = static_cast<int>(hn::Lanes(d16));
  const int slot = pathSlot(D);
  for (int x = x0; x < x1; ++x) {
    std::uint16_t* s = sumRow + static_cast<std::size_t>(x) * D;
    const T* L = path + static_cast<std::size_t>(x) * slot + 1;
    for (int i = 0; i < D; i += N) hn::StoreU(hn::Add(hn::LoadU(d16, s + i), LoadAsU16(L + i)), d16, s + i);
  }
}

// Exported, one per element type (dispatch tables hold plain functions).
void PathRowFromPrevious8(const std::uint8_t* c, int cx0, const std::uint8_t* prev, const std::uint16_t* prevMin,
                          int dx, int w, int x0, int x1, int D, int P1, int P2, std::uint8_t* out, std::uint16_t* outMin,
                          const std::int16_t* first, const std::int16_t* count, const std::uint32_t* costOffset) {
  PathRowFromPreviousT(c, cx0, prev, prevMin, dx, w, x0, x1, D, P1, P2, out, outMin, first, count, costOffset);
}
void PathRowFromPrevious16(const std::uint8_t* c, int cx0, const std::uint16_t* prev, const std::uint16_t* prevMin,
                           int dx, int w, int x0, int x1, int D, int P1, int P2, std::uint16_t* out,
                           std::uint16_t* outMin, const std::int16_t* first, const std::int16_t* count,
                           const std::uint32_t* costOffset) {
  PathRowFromPreviousT(c, cx0, prev, prevMin, dx, w, x0, x1, D, P1, P2, out, outMin, first, count, costOffset);
}
void PathRowHorizontal8(const std::uint8_t* c, int dx, int w, int D, int P1, int P2, std::uint8_t* out) {
  PathRowHorizontalT(c, dx, w, D, P1, P2, out);
}
void PathRowHorizontal16(const std::uint8_t* c, int dx, int w, int D, int P1, int P2, std::uint16_t* out) {
  PathRowHorizontalT(c, dx, w, D, P1, P2, out);
}
void PathRowsHorizontal8(const std::uint8_t* c, int w, int D, int P1, int P2, std::uint8_t* right,
                         std::uint8_t* left, const std::int16_t* first, const std::int16_t* count,
                         const std::uint32_t* costOffset) {
  PathRowsHorizontalT(c, w, D, P1, P2, right, left, first, count, costOffset);
}
void PathRowsHorizontal16(const std::uint8_t* c, int w, int D, int P1, int P2, std::uint16_t* right,
                          std::uint16_t* left, const std::int16_t* first, const std::int16_t* count,
                          const std::uint32_t* costOffset) {
  PathRowsHorizontalT(c, w, D, P1, P2, right, left, first, count, costOffset);
}
void StorePathSum8(const std::uint8_t* const* paths, int count, int x0, int x1, int D, std::uint8_t* s8,
                   std::uint16_t* s16) {
  StorePathSumT(paths, count, x0, x1, D, s8, s16);
}
void StorePathSum16(const std::uint16_t* const* paths, int count, int x0, int x1, int D, std::uint8_t* s8,
                    std::uint16_t* s16) {
  StorePathSumT(paths, count, x0, x1, D, s8, s16);
}
void AddPathRow8(const std::uint8_t* path, int x0, int x1, int D, std::uint16_t* sumRow) {
  AddPathRowT(path, x0, x1, D, sumRow);
}
void AddPathRow16(const std::uint16_t* path, int x0, int x1, int D, std::uint16_t* sumRow) {
  AddPathRowT(path, x0, x1, D, sumRow);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(PathRowFromPrevious8);
HWY_EXPORT(PathRowFromPrevious16);
HWY_EXPORT(PathRowHorizontal8);
HWY_EXPORT(PathRowHorizontal16);
HWY_EXPORT(PathRowsHorizontal8);
HWY_EXPORT(PathRowsHorizontal16);
HWY_EXPORT(StorePathSum8);
HWY_EXPORT(StorePathSum16);
HWY_EXPORT(AddPathRow8);
HWY_EXPORT(AddPathRow16);

bool pathCostsFit8Bits(int maxCost, int P2) { return largestPathCost(maxCost, P2) <= 255; }

void pathRowFromPrevious(const std::uint8_t* costRow, int costX0, const std::uint8_t* previous,
                         const std::uint16_t* previousMin, int dx, int width, int x0, int x1, int numDisparities,
                         int P1, int P2, std::uint8_t* out, std::uint16_t* outMin, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(PathRowFromPrevious8)(costRow, costX0, previous, previousMin, dx, width, x0, x1, numDisparities,
                                             P1, P2, out, outMin, windows.first, windows.count,
                                             windows.costOffset);
}
void pathRowFromPrevious(const std::uint8_t* costRow, int costX0, const std::uint16_t* previous,
                         const std::uint16_t* previousMin, int dx, int width, int x0, int x1, int numDisparities,
                         int P1, int P2, std::uint16_t* out, std::uint16_t* outMin, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(PathRowFromPrevious16)(costRow, costX0, previous, previousMin, dx, width, x0, x1,
                                              numDisparities, P1, P2, out, outMin, windows.first, windows.count,
                                             windows.costOffset);
}
void pathRowHorizontal(const std::uint8_t* costRow, int dx, int width, int numDisparities, int P1, int P2,
                       std::uint8_t* out) {
  HWY_DYNAMIC_DISPATCH(PathRowHorizontal8)(costRow, dx, width, numDisparities, P1, P2, out);
}
void pathRowHorizontal(const std::uint8_t* costRow, int dx, int width, int numDisparities, int P1, int P2,
                       std::uint16_t* out) {
  HWY_DYNAMIC_DISPATCH(PathRowHorizontal16)(costRow, dx, width, numDisparities, P1, P2, out);
}
void pathRowsHorizontal(const std::uint8_t* costRow, int width, int numDisparities, int P1, int P2,
                        std::uint8_t* rightward, std::uint8_t* leftward, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(PathRowsHorizontal8)(costRow, width, numDisparities, P1, P2, rightward, leftward,
                                            windows.first, windows.count, windows.costOffset);
}
void pathRowsHorizontal(const std::uint8_t* costRow, int width, int numDisparities, int P1, int P2,
                        std::uint16_t* rightward, std::uint16_t* leftward, RowWindows windows) {
  HWY_DYNAMIC_DISPATCH(PathRowsHorizontal16)(costRow, width, numDisparities, P1, P2, rightward, leftward,
                                             windows.first, windows.count, windows.costOffset);
}
void storePathSum(const std::uint8_t* const* paths, int count, int x0, int x1, int numDisparities,
                  std::uint8_t* stored8, std::uint16_t* stored16) {
  HWY_DYNAMIC_DISPATCH(StorePathSum8)(paths, count, x0, x1, numDisparities, stored8, stored16);
}
void storePathSum(const std::uint16_t* const* paths, int count, int x0, int x1, int numDisparities,
                  std::uint8_t* stored8, std::uint16_t* stored16) {
  HWY_DYNAMIC_DISPATCH(StorePathSum16)(paths, count, x0, x1, numDisparities, stored8, stored16);
}
void addPathRow(const std::uint8_t* path, int x0, int x1, int numDisparities, std::uint16_t* sumRow) {
  HWY_DYNAMIC_DISPATCH(AddPathRow8)(path, x0, x1, numDisparities, sumRow);
}
void addPathRow(const std::uint16_t* path, int x0, int x1, int numDisparities, std::uint16_t* sumRow) {
  HWY_DYNAMIC_DISPATCH(AddPathRow16)(path, x0, x1, numDisparities, sumRow);
}

namespace {

template <typename T>
void aggregatePathsT(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum,
                     int threads) {
  const int width = cost.width();
  const int height = cost.height();
  const int D = cost.numDisparities();
  sum.resize(width, height, D);
  std::fill(sum.data(), sum.data() + sum.size(), std::uint16_t{0});
  // Horizontal paths: every row is independent, so rows are split among the threads.
  parallelRanges(height, threads, [&](int y0, int y1) {
    std::vector<T> row = pathRowBuffer<T>(width, D);
    for (int y = y0; y < y1; ++y) {
      for (const int dx : {1, -1}) {
        pathRowHorizontal(cost.at(0, y), dx, width, D, P1, P2, row.data());
        addPathRow(row.data(), 0, width, D, sum.at(0, y));
      }
    }
  });
  // Vertical and diagonal paths: rows in path order, the columns of a row split among threads.
  std::vector<T> rows[2] = {pathRowBuffer<T>(width, D), pathRowBuffer<T>(width, D)};
  std::vector<std::uint16_t> mins[2] = {std::vector<std::uint16_t>(width), std::vector<std::uint16_t>(width)};
  for (int r = 2; r < paths; ++r) {
    const PathDirection dir = kPathDirections[r];
    for (int i = 0; i < height; ++i) {
      const int y = dir.dy > 0 ? i : height - 1 - i;
      std::vector<T>& current = rows[i % 2];
      const std::vector<T>& previous = rows[(i + 1) % 2];
      parallelRanges(width, threads, [&](int x0, int x1) {
        pathRowFromPrevious(cost.at(0, y), 0, i == 0 ? nullptr : previous.data(), mins[(i + 1) % 2].data(), dir.dx,
                            width, x0, x1, D, P1, P2, current.data(), mins[i % 2].data());
        addPathRow(current.data(), x0, x1, D, sum.at(0, y));
      });
    }
  }
}

}  // namespace

void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum,
                    int threads) {
  // The volume does not say which costs it holds: its largest value bounds them.
  if (pathCostsFit8Bits(largestMatchingCost(cost), P2)) {
    aggregatePathsT<std::uint8_t>(cost, P1, P2, paths, sum, threads);
  } else {
    aggregatePathsT<std::uint16_t>(cost, P1, P2, paths, sum, threads);
  }
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
