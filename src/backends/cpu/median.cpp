// Median filter over valid disparities, fast CPU backend. Where the whole window lies inside
// the image, a selection network finds the median of 16 pixels at once in 16-bit lanes: the
// partial network for the median of 25 where every pixel is valid (most pixels), else a full
// sort in which the invalid marker (the smallest int16) sorts first, so each lane's lower
// median of its valid pixels sits at index invalid + (valid - 1) / 2 (a merge sort network,
// kSort25, for the 5x5 windows). Windows cut by the image border take cpu_ref's path.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/median.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

#ifndef LIDAR_SGM_CPU_MEDIAN_ONCE  // Highway compiles this file once per target; this once only.
#define LIDAR_SGM_CPU_MEDIAN_ONCE
namespace lidar_sgm {
namespace cpu {
namespace {

// cpu_ref's rule for one pixel: the lower median of the valid pixels of the clamped window.
std::int16_t medianPixel(ImageView<const std::int16_t> in, int radius, int x, int y) {
  std::int16_t window[25];
  int n = 0;
  for (int ny = std::max(0, y - radius); ny <= std::min(in.height - 1, y + radius); ++ny) {
    for (int nx = std::max(0, x - radius); nx <= std::min(in.width - 1, x + radius); ++nx) {
      if (in(nx, ny) != kInvalidDisparity) window[n++] = in(nx, ny);
    }
  }
  std::nth_element(window, window + (n - 1) / 2, window + n);
  return window[(n - 1) / 2];
}

// Batcher's odd-even merge sort of 32 inputs, less every comparator that touches an input at or
// past 25: with those 7 set to the largest value they never move (a comparator puts the smaller
// value first), so the rest sorts 25 values with 140 comparators instead of a selection sort's 300.
struct Comparator {
  std::uint8_t a, b;
};
constexpr int oddEvenMergeSort25(Comparator* out) {
  constexpr int n = 32;
  int count = 0;
  for (int p = 1; p < n; p <<= 1) {
    for (int k = p; k >= 1; k >>= 1) {
      for (int j = k % p; j + k < n; j += 2 * k) {
        for (int i = 0; i < k && i + j + k < n; ++i) {
          if ((i + j) / (2 * p) != (i + j + k) / (2 * p) || i + j + k >= 25) continue;
          if (out != nullptr) out[count] = {static_cast<std::uint8_t>(i + j), static_cast<std::uint8_t>(i + j + k)};
          ++count;
        }
      }
    }
  }
  return count;
}
constexpr int kSort25Size = oddEvenMergeSort25(nullptr);
constexpr std::array<Comparator, kSort25Size> kSort25 = [] {
  std::array<Comparator, kSort25Size> network{};
  oddEvenMergeSort25(network.data());
  return network;
}();

}  // namespace
}  // namespace cpu
}  // namespace lidar_sgm
#endif  // LIDAR_SGM_CPU_MEDIAN_ONCE

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DI16 = hn::CappedTag<std::int16_t, 16>;
using VI16 = hn::Vec<DI16>;

// Partial selection sort as a network: after round i, v[i] is the i-th smallest; the median of
// n = 2k + 1 values is v[k] after round k.
template <int n>
HWY_INLINE VI16 SelectMedian(VI16* v) {
  for (int i = 0; i <= n / 2; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const VI16 lo = hn::Min(v[i], v[j]);
      v[j] = hn::Max(v[i], v[j]);
      v[i] = lo;
    }
  }
  return v[n / 2];
}

// Per lane of `sorted` (ascending, the invalid marker first): the lower median of the valid
// values, at index invalid + (valid - 1) / 2.
template <int n>
HWY_INLINE VI16 PickValidMedian(const VI16* sorted, VI16 invalidCount) {
  const DI16 d;
  const auto valid = hn::Sub(hn::Set(d, static_cast<std::int16_t>(n)), invalidCount);
  const auto target = hn::Add(invalidCount, hn::ShiftRight<1>(hn::Sub(valid, hn::Set(d, std::int16_t{1}))));
  VI16 median = sorted[0];
  for (int i = 1; i < n; ++i) {
    median = hn::IfThenElse(hn::Eq(target, hn::Set(d, static_cast<std::int16_t>(i))), sorted[i], median);
  }
  return median;
}

// Full sort network (selection sort), then per lane the lower median of the valid values.
template <int n>
HWY_INLINE VI16 SelectValidMedian(VI16* v, VI16 invalidCount) {
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const VI16 lo = hn::Min(v[i], v[j]);
      v[j] = hn::Max(v[i], v[j]);
      v[i] = lo;
    }
  }
  return PickValidMedian<n>(v, invalidCount);
}

HWY_INLINE void CompareExchange(VI16& a, VI16& b) {
  const VI16 lo = hn::Min(a, b);
  b = hn::Max(a, b);
  a = lo;
}

// The 25 values sorted by the pruned merge sort network kSort25, then per lane the lower median
// of the valid values (as SelectValidMedian, with 140 comparators instead of 300), for the windows
// of the 5x5 filter that hold an invalid pixel.
HWY_INLINE VI16 SortValidMedian25(VI16* v, VI16 invalidCount) {
  for (const Comparator& c : kSort25) CompareExchange(v[c.a], v[c.b]);
  return PickValidMedian<25>(v, invalidCount);
}

// Knuth's optimal 9-comparator network for 5 values.
HWY_INLINE void Sort5(VI16& v0, VI16& v1, VI16& v2, VI16& v3, VI16& v4) {
  CompareExchange(v0, v1);
  CompareExchange(v3, v4);
  CompareExchange(v2, v4);
  CompareExchange(v2, v3);
  CompareExchange(v0, v3);
  CompareExchange(v0, v2);
  CompareExchange(v1, v4);
  CompareExchange(v1, v3);
  CompareExchange(v1, v2);
}

// The median of a 5x5 window from its five columns, each already sorted (A[k][j]: the k-th
// smallest of column j). Sorting the five rank-rows keeps the columns sorted; then A[k][j] has at
// least (k+1)(j+1) - 1 values at or below it and (5-k)(5-j) - 1 at or above it, so the 6 entries
// with (5-k)(5-j) > 13 lie below the median, the 6 with (k+1)(j+1) > 13 above it, and the median
// of 25 is the median of the 13 others. 45 + 63 comparators instead of the 234 of a selection
// over all 25.
HWY_INLINE VI16 MedianOfSortedColumns(VI16 (&A)[5][5]) {
  for (int k = 0; k < 5; ++k) Sort5(A[k][0], A[k][1], A[k][2], A[k][3], A[k][4]);
  VI16 candidates[13] = {A[0][3], A[0][4], A[1][2], A[1][3], A[1][4], A[2][1], A[2][2],
                         A[2][3], A[3][0], A[3][1], A[3][2], A[4][0], A[4][1]};
  return SelectMedian<13>(candidates);
}

// The n = 5 * rows values of the 5x5 windows of pixels at .. at + N - 1 cut to the rows from
// `firstRow` on, into v; returns per lane how many of them are invalid.
template <int n>
HWY_INLINE VI16 LoadWindows(ImageView<const std::int16_t> in, int firstRow, int at, VI16* v) {
  const DI16 d;
  const auto invalid = hn::Set(d, kInvalidDisparity);
  auto invalidCount = hn::Zero(d);  // minus the count: a true mask is -1
  for (int k = 0; k < n; ++k) {
    v[k] = hn::LoadU(d, in.row(firstRow + k / 5) + at - 2 + k % 5);
    invalidCount = hn::Add(invalidCount, hn::VecFromMask(d, hn::Eq(v[k], invalid)));
  }
  return hn::Neg(invalidCount);
}

// The medians of pixels at .. at + N - 1 of row y, except where the pixel itself is invalid: the
// median removes outliers, it does not fill holes.
HWY_INLINE void StoreUnlessInvalid(ImageView<const std::int16_t> in, int y, int at, VI16 median, std::int16_t* out) {
  const DI16 d;
  const auto invalid = hn::Set(d, kInvalidDisparity);
  hn::StoreU(hn::IfThenElse(hn::Eq(hn::LoadU(d, in.row(y) + at), invalid), invalid, median), d, out + at);
}

// Row y of the 5x5 median along its columns: `medians(x)` for the pixels x .. x + N - 1 whose
// windows' five columns are inside the image, cpu_ref's rule pixel by pixel for the two columns
// at each edge.
template <class Medians>
HWY_INLINE void Median5Columns(ImageView<const std::int16_t> in, int y, int N, const Medians& medians,
                               std::int16_t* out) {
  const int width = in.width;
  int x = 0;
  for (; x < 2; ++x) out[x] = in(x, y) == kInvalidDisparity ? kInvalidDisparity : medianPixel(in, 2, x, y);
  for (; x + N + 2 <= width; x += N) medians(x);
  if (x < width - 2 && width >= N + 4) {
    // The last windows inside the image: one more vector ending there, over pixels the loop
    // already wrote (the same values again: out is not in), instead of one scalar window each.
    medians(width - 2 - N);
    x = width - 2;
  }
  for (; x < width; ++x) out[x] = in(x, y) == kInvalidDisparity ? kInvalidDisparity : medianPixel(in, 2, x, y);
}

// One output row of the 5x5 median where the window is inside the image. The five-pixel columns
// (rows y-2 .. y+2) are sorted once per row into `columns` (5 rank rows of `width`), then every
// window reads its five sorted columns; windows with an invalid pixel (the invalid marker is the
// smallest int16, so it is a column's rank 0) take the full sort of SortValidMedian25.
void Median5RowInside(ImageView<const std::int16_t> in, int y, std::int16_t* columns, std::int16_t* out) {
  const DI16 d;
  const int N = static_cast<int>(hn::Lanes(d));
  const int width = in.width;
  const auto invalid = hn::Set(d, kInvalidDisparity);
  std::int16_t* rank[5];
  for (int k = 0; k < 5; ++k) rank[k] = columns + static_cast<std::size_t>(k) * width;
  int x = 0;
  for (; x + N <= width; x += N) {
    VI16 v0 = hn::LoadU(d, in.row(y - 2) + x), v1 = hn::LoadU(d, in.row(y - 1) + x), v2 = hn::LoadU(d, in.row(y) + x);
    VI16 v3 = hn::LoadU(d, in.row(y + 1) + x), v4 = hn::LoadU(d, in.row(y + 2) + x);
    Sort5(v0, v1, v2, v3, v4);
    hn::StoreU(v0, d, rank[0] + x);
    hn::StoreU(v1, d, rank[1] + x);
    hn::StoreU(v2, d, rank[2] + x);
    hn::StoreU(v3, d, rank[3] + x);
    hn::StoreU(v4, d, rank[4] + x);
  }
  for (; x < width; ++x) {
    std::int16_t c[5] = {in(x, y - 2), in(x, y - 1), in(x, y), in(x, y + 1), in(x, y + 2)};
    std::sort(c, c + 5);
    for (int k = 0; k < 5; ++k) rank[k][x] = c[k];
  }
  // The windows of the N pixels from `at` on (all inside the image).
  const auto medians = [&](int at) {
    auto anyInvalid = hn::Eq(hn::LoadU(d, rank[0] + at - 2), invalid);
    for (int j = 1; j < 5; ++j) anyInvalid = hn::Or(anyInvalid, hn::Eq(hn::LoadU(d, rank[0] + at - 2 + j), invalid));
    if (hn::AllFalse(d, anyInvalid)) {
      VI16 A[5][5];
      for (int k = 0; k < 5; ++k) {
        for (int j = 0; j < 5; ++j) A[k][j] = hn::LoadU(d, rank[k] + at - 2 + j);
      }
      hn::StoreU(MedianOfSortedColumns(A), d, out + at);
      return;
    }
    VI16 v[25];
    const VI16 invalidCount = LoadWindows<25>(in, y - 2, at, v);
    StoreUnlessInvalid(in, y, at, SortValidMedian25(v, invalidCount), out);
  };
  Median5Columns(in, y, N, medians, out);
}

// One output row of the 5x5 median where the window is cut by the top or bottom of the image: its
// `kRows` rows inside the image (rows first .. first + kRows - 1), 5 kRows values per window, of
// which the lower median of the valid ones as cpu_ref takes it (a full sort; the invalid marker
// sorts first). Columns within 2 of the left or right edge take cpu_ref's path.
template <int kRows>
void Median5RowCut(ImageView<const std::int16_t> in, int y, int first, std::int16_t* out) {
  constexpr int n = 5 * kRows;
  const int N = static_cast<int>(hn::Lanes(DI16()));
  const auto medians = [&](int at) {
    VI16 v[n];
    const VI16 invalidCount = LoadWindows<n>(in, first, at, v);
    StoreUnlessInvalid(in, y, at, SelectValidMedian<n>(v, invalidCount), out);
  };
  Median5Columns(in, y, N, medians, out);
}

// The 3x3 filter's row (the 5x5 filter has Median5RowInside and the scalar rule at its edges).
template <int size>
void MedianRowSized(ImageView<const std::int16_t> in, int y, std::int16_t* out) {
  constexpr int radius = size / 2;
  const DI16 d;
  const int N = static_cast<int>(hn::Lanes(d));
  const auto invalid = hn::Set(d, kInvalidDisparity);
  int x = 0;
  const bool rowInside = y >= radius && y + radius < in.height;
  if (rowInside) {
    for (; x < radius; ++x) out[x] = in(x, y) == kInvalidDisparity ? kInvalidDisparity : medianPixel(in, radius, x, y);
    for (; x + N + radius <= in.width; x += N) {
      VI16 v[size * size];
      auto invalidCount = hn::Zero(d);  // minus the count: a true mask is -1
      int k = 0;
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          v[k] = hn::LoadU(d, in.row(y + dy) + x + dx);
          invalidCount = hn::Add(invalidCount, hn::VecFromMask(d, hn::Eq(v[k], invalid)));
          ++k;
        }
      }
      const auto centre = hn::LoadU(d, in.row(y) + x);
      if (hn::AllTrue(d, hn::Eq(invalidCount, hn::Zero(d)))) {
        hn::StoreU(SelectMedian<size * size>(v), d, out + x);
      } else {
        // An invalid pixel stays invalid: the median removes outliers, it does not fill holes.
        const auto median = SelectValidMedian<size * size>(v, hn::Neg(invalidCount));
        hn::StoreU(hn::IfThenElse(hn::Eq(centre, invalid), invalid, median), d, out + x);
      }
    }
  }
  for (; x < in.width; ++x) out[x] = in(x, y) == kInvalidDisparity ? kInvalidDisparity : medianPixel(in, radius, x, y);
}

void MedianRowImpl(ImageView<const std::int16_t> in, int size, int y, std::int16_t* columns, std::int16_t* out) {
  if (size == 5 && y >= 2 && y + 2 < in.height && in.width >= 5) {
    Median5RowInside(in, y, columns, out);
  } else if (size == 5 && in.width >= 5) {
    // The two rows at each edge: the window's rows inside the image.
    const int first = std::max(0, y - 2);
    switch (std::min(in.height - 1, y + 2) - first + 1) {
      case 1: Median5RowCut<1>(in, y, first, out); break;
      case 2: Median5RowCut<2>(in, y, first, out); break;
      case 3: Median5RowCut<3>(in, y, first, out); break;
      default: Median5RowCut<4>(in, y, first, out); break;
    }
  } else if (size == 5) {
    // Images narrower than the window: narrower than any vector too, so pixel by pixel.
    for (int x = 0; x < in.width; ++x) out[x] = in(x, y) == kInvalidDisparity ? kInvalidDisparity : medianPixel(in, 2, x, y);
  } else if (size == 3) {
    MedianRowSized<3>(in, y, out);
  } else {
    std::copy(in.row(y), in.row(y) + in.width, out);  // size 0 or 1: a copy
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(MedianRowImpl);

void medianRow(ImageView<const std::int16_t> in, int size, int y, std::int16_t* columns, std::int16_t* out) {
  HWY_DYNAMIC_DISPATCH(MedianRowImpl)(in, size, y, columns, out);
}

void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out, int threads) {
  parallelRanges(in.height, threads, [&](int y0, int y1) {
    // The row's sorted columns; kept per thread, so a frame after the first allocates nothing.
    thread_local std::vector<std::int16_t> columns;
    if (columns.size() < 5 * static_cast<std::size_t>(in.width)) columns.resize(5 * static_cast<std::size_t>(in.width));
    for (int y = y0; y < y1; ++y) medianRow(in, size, y, columns.data(), out.row(y));
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
