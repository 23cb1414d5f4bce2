// Census transform, fast CPU backend: 8 pixels at a time in 32-bit lanes. The 62 comparisons
// of the 9x7 window go to two words (the first 30 to the high word, the last 32 to the low
// one), which gives cpu_ref's MSB-first raster order once the words are joined.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/census.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

#ifndef LIDAR_SGM_CPU_CENSUS_ONCE  // Highway compiles this file once per target; these once only.
#define LIDAR_SGM_CPU_CENSUS_ONCE
namespace lidar_sgm {
namespace cpu {
namespace {

constexpr int kHalfWidth = 4;   // 9 columns
constexpr int kHalfHeight = 3;  // 7 rows
constexpr int kHighBits = 30;   // comparisons 0..29 land in bits 61..32

// cpu_ref's loop for one pixel, with the window clamped at the border.
template <typename Pixel>
std::uint64_t censusPixel(const Pixel* const* rows, int width, int x, CensusType type) {
  const auto at = [&](int dx, int dy) { return rows[dy + kHalfHeight][std::clamp(x + dx, 0, width - 1)]; };
  std::uint64_t bits = 0;
  if (type == CensusType::Census9x7) {
    const Pixel centre = at(0, 0);
    for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
      for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
        if (dx == 0 && dy == 0) continue;
        bits = (bits << 1) | (at(dx, dy) < centre ? 1u : 0u);
      }
    }
  } else {
    for (int dy = -kHalfHeight; dy <= 0; ++dy) {
      for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
        if (dy == 0 && dx >= 0) break;
        bits = (bits << 1) | (at(dx, dy) < at(-dx, -dy) ? 1u : 0u);
      }
    }
  }
  return bits;
}

}  // namespace
}  // namespace cpu
}  // namespace lidar_sgm
#endif  // LIDAR_SGM_CPU_CENSUS_ONCE

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D32 = hn::CappedTag<std::int32_t, 8>;

template <typename Pixel>
void CensusRowImpl(ImageView<const Pixel> image, CensusType type, int y, int x0, int x1, std::uint64_t* out) {
  const D32 d32;
  const hn::Rebind<Pixel, D32> dp;
  const int N = static_cast<int>(hn::Lanes(d32));
  const int width = image.width;
  const Pixel* rows[2 * kHalfHeight + 1];
  for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
    rows[dy + kHalfHeight] = image.row(std::clamp(y + dy, 0, image.height - 1));  // border rows repeat
  }
  const auto load = [&](int dy, int x) { return hn::PromoteTo(d32, hn::LoadU(dp, rows[dy + kHalfHeight] + x)); };
  HWY_ALIGN std::int32_t high[8];
  HWY_ALIGN std::int32_t low[8];
  int x = x0;
  for (; x < std::min(kHalfWidth, x1); ++x) out[x] = censusPixel(rows, width, x, type);
  // Whole vectors wherever the window stays inside the row.
  for (; x + N + kHalfWidth <= width && x + N <= x1; x += N) {
    if (type == CensusType::Census9x7) {
      const auto centre = load(0, x);
      auto hi = hn::Zero(d32);
      auto lo = hn::Zero(d32);
      int k = 0;
      for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
        for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
          if (dx == 0 && dy == 0) continue;
          // bits = (bits << 1) | (neighbour < centre): the all-ones mask is -1, so subtracting adds 1.
          const auto lt = hn::VecFromMask(d32, hn::Lt(load(dy, x + dx), centre));
          if (k++ < kHighBits) {
            hi = hn::Sub(hn::ShiftLeft<1>(hi), lt);
          } else {
            lo = hn::Sub(hn::ShiftLeft<1>(lo), lt);
          }
        }
      }
      hn::Store(hi, d32, high);
      hn::Store(lo, d32, low);
      for (int i = 0; i < N; ++i) {
        out[x + i] = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(high[i])) << 32) |
                     static_cast<std::uint32_t>(low[i]);
      }
    } else {
      auto bits = hn::Zero(d32);
      for (int dy = -kHalfHeight; dy <= 0; ++dy) {
        for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
          if (dy == 0 && dx >= 0) break;
          const auto lt = hn::VecFromMask(d32, hn::Lt(load(dy, x + dx), load(-dy, x - dx)));
          bits = hn::Sub(hn::ShiftLeft<1>(bits), lt);
        }
      }
      hn::Store(bits, d32, low);
      for (int i = 0; i < N; ++i) out[x + i] = static_cast<std::uint32_t>(low[i]);
    }
  }
  for (; x < x1; ++x) out[x] = censusPixel(rows, width, x, type);
}

void CensusRow8Impl(ImageView<const std::uint8_t> image, CensusType type, int y, int x0, int x1,
                    std::uint64_t* out) {
  CensusRowImpl(image, type, y, x0, x1, out);
}
void CensusRow16Impl(ImageView<const std::uint16_t> image, CensusType type, int y, int x0, int x1,
                     std::uint64_t* out) {
  CensusRowImpl(image, type, y, x0, x1, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(CensusRow8Impl);
HWY_EXPORT(CensusRow16Impl);

void censusTransformRow(ImageView<const std::uint8_t> image, CensusType type, int y, std::uint64_t* out) {
  HWY_DYNAMIC_DISPATCH(CensusRow8Impl)(image, type, y, 0, image.width, out);
}
void censusTransformRow(ImageView<const std::uint16_t> image, CensusType type, int y, std::uint64_t* out) {
  HWY_DYNAMIC_DISPATCH(CensusRow16Impl)(image, type, y, 0, image.width, out);
}
void censusTransformRow(ImageView<const std::uint8_t> image, CensusType type, int y, int x0, int x1,
                        std::uint64_t* out) {
  HWY_DYNAMIC_DISPATCH(CensusRow8Impl)(image, type, y, x0, x1, out);
}
void censusTransformRow(ImageView<const std::uint16_t> image, CensusType type, int y, int x0, int x1,
                        std::uint64_t* out) {
  HWY_DYNAMIC_DISPATCH(CensusRow16Impl)(image, type, y, x0, x1, out);
}

void censusTransform(ImageView<const std::uint8_t> image, CensusType type, ImageView<std::uint64_t> census,
                     int threads) {
  parallelRanges(image.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) censusTransformRow(image, type, y, census.row(y));
  });
}
void censusTransform(ImageView<const std::uint16_t> image, CensusType type, ImageView<std::uint64_t> census,
                     int threads) {
  parallelRanges(image.height, threads, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) censusTransformRow(image, type, y, census.row(y));
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
