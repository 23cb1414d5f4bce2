// removeOutliers (outlier_filter.cpp, the specification), fast: the neighbours of similar depth
// are counted for a vector of pixels at once, one window offset after another, on a copy of the
// input whose rows carry `radius` invalid columns on each side (so that columns outside the image
// count as invalid, as the specification skips them). Every decision reads the copy, so the row
// ranges of the threads are independent. The specification stops counting at minNeighbours; the
// full count decides the same.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pipeline/fast/outlier_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace fast {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The similarity tolerance of each pixel of a row, x16: max(minTolerance16, relative1024 * |d| / 1024)
// (at most 32767). Invalid pixels get one too; it is never read for them.
void ToleranceRow(const std::int16_t* HWY_RESTRICT d, int width, int minTolerance16, int relative1024,
                  std::uint16_t* HWY_RESTRICT tolerance) {
  for (int x = 0; x < width; ++x) {
    const int magnitude = std::abs(static_cast<int>(d[x]));  // <= 32768: the product fits 31 bits
    tolerance[x] = static_cast<std::uint16_t>(std::max(minTolerance16, (relative1024 * magnitude) >> 10));
  }
}

// One row: `rows[k]` points at the padded copy's column 0 of window row k (null outside the
// image), `self` at the row's own; the row's pixels with fewer similar neighbours than
// `minNeighbours` become invalid in `out`. Returns how many.
std::size_t OutlierRowImpl(const std::int16_t* const* rows, int windowRows, int selfRow, int radius, int width,
                           const std::uint16_t* HWY_RESTRICT tolerance, int minNeighbours,
                           std::int16_t* HWY_RESTRICT out) {
  const hn::ScalableTag<std::int16_t> di;
  const hn::RebindToUnsigned<decltype(di)> du;
  const int N = static_cast<int>(hn::Lanes(di));
  const auto invalid = hn::Set(di, kInvalidDisparity);
  const auto needed = hn::Set(di, static_cast<std::int16_t>(minNeighbours));
  const std::int16_t* self = rows[selfRow];
  std::size_t removed = 0;
  int x = 0;
  for (; x + N <= width; x += N) {
    const auto d = hn::LoadU(di, self + x);
    const auto tol = hn::LoadU(du, tolerance + x);
    auto similar = hn::Zero(di);
    for (int k = 0; k < windowRows; ++k) {
      if (rows[k] == nullptr) continue;
      for (int dx = -radius; dx <= radius; ++dx) {
        if (k == selfRow && dx == 0) continue;
        const auto q = hn::LoadU(di, rows[k] + x + dx);
        // |q - d| as uint16 (exact: the true difference lies in [0, 65535]).
        const auto difference = hn::BitCast(du, hn::Sub(hn::Max(q, d), hn::Min(q, d)));
        const auto close = hn::Eq(hn::SaturatedSub(difference, tol), hn::Zero(du));
        const auto counted = hn::And(hn::RebindMask(di, close), hn::Ne(q, invalid));
        similar = hn::Sub(similar, hn::VecFromMask(di, counted));  // a true lane is -1
      }
    }
    const auto drop = hn::And(hn::Ne(d, invalid), hn::Lt(similar, needed));
    removed += hn::CountTrue(di, drop);
    hn::StoreU(hn::IfThenElse(drop, invalid, d), di, out + x);
  }
  for (; x < width; ++x) {  // the tail, pixel by pixel, with the same rule
    const int d = self[x];
    if (d == kInvalidDisparity) {
      out[x] = static_cast<std::int16_t>(d);
      continue;
    }
    int similar = 0;
    for (int k = 0; k < windowRows; ++k) {
      if (rows[k] == nullptr) continue;
      for (int dx = -radius; dx <= radius; ++dx) {
        const int q = rows[k][x + dx];
        if ((k == selfRow && dx == 0) || q == kInvalidDisparity) continue;
        if (std::abs(q - d) <= tolerance[x]) ++similar;
      }
    }
    const bool drop = similar < minNeighbours;
    removed += drop ? 1 : 0;
    out[x] = drop ? kInvalidDisparity : static_cast<std::int16_t>(d);
  }
  return removed;
}

}  // namespace HWY_NAMESPACE
}  // namespace fast
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace fast {

HWY_EXPORT(ToleranceRow);
HWY_EXPORT(OutlierRowImpl);

std::size_t removeOutliers(ImageView<std::int16_t> disparity16, const OutlierFilterOptions& options,
                           FastPassBuffers& buffers, int threads) {
  validate(options);
  if (!options.enabled || options.minNeighbours == 0) return 0;
  const int width = disparity16.width;
  const int height = disparity16.height;
  const int r = options.radius;
  const std::size_t padded = static_cast<std::size_t>(width) + 2 * r;
  // The tolerances as the specification rounds them.
  const int minTolerance16 = static_cast<int>(std::lround(options.minTolerance * kDisparityScale));
  const int relative1024 = static_cast<int>(std::lround(options.relativeTolerance * 1024.0));
  // The copy, and one tolerance row per range after it.
  const int ranges = rangeCount(height, threads);
  const std::size_t copySize = padded * height;
  if (buffers.paddedDisparity.size() < copySize + padded * ranges) {
    buffers.paddedDisparity.resize(copySize + padded * ranges);
  }
  std::int16_t* copy = buffers.paddedDisparity.data();
  parallelRanges(height, threads, [&](int, int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      std::int16_t* row = copy + padded * y;
      std::fill(row, row + r, kInvalidDisparity);
      std::copy(disparity16.row(y), disparity16.row(y) + width, row + r);
      std::fill(row + r + width, row + padded, kInvalidDisparity);
    }
  });
  buffers.removedPerRange.assign(static_cast<std::size_t>(ranges), 0);
  parallelRanges(height, threads, [&](int t, int y0, int y1) {
    // The tolerances fit int16's positive half: stored as uint16 in this range's row.
    auto* tolerance = reinterpret_cast<std::uint16_t*>(copy + copySize + padded * t);
    const std::int16_t* rows[2 * 8 + 1];
    std::size_t removed = 0;
    for (int y = y0; y < y1; ++y) {
      for (int k = 0; k <= 2 * r; ++k) {
        const int yy = y - r + k;
        rows[k] = yy >= 0 && yy < height ? copy + padded * yy + r : nullptr;
      }
      HWY_DYNAMIC_DISPATCH(ToleranceRow)(rows[r], width, minTolerance16, relative1024, tolerance);
      removed += HWY_DYNAMIC_DISPATCH(OutlierRowImpl)(rows, 2 * r + 1, r, r, width, tolerance, options.minNeighbours,
                                                      disparity16.row(y));
    }
    buffers.removedPerRange[static_cast<std::size_t>(t)] = removed;
  });
  std::size_t removed = 0;
  for (const std::size_t n : buffers.removedPerRange) removed += n;
  return removed;
}

}  // namespace fast
}  // namespace lidar_sgm
#endif  // HWY_ONCE
