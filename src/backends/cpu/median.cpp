// Median filter over valid disparities, fast CPU backend. Where the whole window lies inside
// the image, a selection network finds the median of 16 pixels at once in 16-bit lanes: the
// partial network for the median of 25 where every pixel is valid (most pixels), else a full
// sort in which the invalid marker (the smallest int16) sorts first, so each lane's lower
// median of its valid pixels sits at index invalid + (valid - 1) / 2. Windows cut by the image
// border take cpu_ref's path.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/median.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>

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

// Full sort network (selection sort), then per lane the lower median of the valid values.
template <int n>
HWY_INLINE VI16 SelectValidMedian(VI16* v, VI16 invalidCount) {
  const DI16 d;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const VI16 lo = hn::Min(v[i], v[j]);
      v[j] = hn::Max(v[i], v[j]);
      v[i] = lo;
    }
  }
  const auto valid = hn::Sub(hn::Set(d, static_cast<std::int16_t>(n)), invalidCount);
  const auto target = hn::Add(invalidCount, hn::ShiftRight<1>(hn::Sub(valid, hn::Set(d, std::int16_t{1}))));
  VI16 median = v[0];
  for (int i = 1; i < n; ++i) median = hn::IfThenElse(hn::Eq(target, hn::Set(d, static_cast<std::int16_t>(i))), v[i], median);
  return median;
}

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

void MedianRowImpl(ImageView<const std::int16_t> in, int size, int y, std::int16_t* out) {
  if (size == 5) {
    MedianRowSized<5>(in, y, out);
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

void medianRow(ImageView<const std::int16_t> in, int size, int y, std::int16_t* out) {
  HWY_DYNAMIC_DISPATCH(MedianRowImpl)(in, size, y, out);
}

void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out, int threads) {
  parallelRanges(in.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) medianRow(in, size, y, out.row(y));
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
