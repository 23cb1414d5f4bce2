// Census transform, fast CPU backend: 8 pixels at a time in 32-bit lanes. The 62 comparisons
// of the 9x7 window go to two words (the first 30 to the high word, the last 32 to the low
// one), which gives cpu_ref's MSB-first raster order once the words are joined. An 8-bit
// image's 9x7 census takes 16-bit lanes and four words instead (Census9x7Bytes): twice the
// pixels a vector.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/census.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <array>

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
using D16 = hn::CappedTag<std::int16_t, 16>;

// The 9x7 census of an 8-bit row, pixels x .. x1-1 from x on, as far as whole vectors of 16-bit
// lanes reach (twice the pixels a vector of the 32-bit version holds): the 62 comparisons go to
// four 16-bit words, comparison j to bit 61 - j of the string as in cpu_ref (the first 14 to the
// top word, then 16 to each of the others), joined per pixel at the end. Returns the first pixel
// not done.
int Census9x7Bytes(const std::uint8_t* const* rows, int width, int x, int x1, std::uint64_t* out) {
  const D16 d16;
  const hn::Rebind<std::uint8_t, D16> d8;
  const int N = static_cast<int>(hn::Lanes(d16));
  const auto load = [&](int dy, int at) { return hn::PromoteTo(d16, hn::LoadU(d8, rows[dy + kHalfHeight] + at)); };
  HWY_ALIGN std::int16_t words[4][16];
  // Comparison j's neighbour in raster order, the centre left out.
  static constexpr auto kNeighbours = [] {
    std::array<std::array<int, 2>, 62> n{};
    int j = 0;
    for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
      for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
        if (dx != 0 || dy != 0) n[static_cast<std::size_t>(j++)] = {dy, dx};
      }
    }
    return n;
  }();
  for (; x + N + kHalfWidth <= width && x + N <= x1; x += N) {
    const auto centre = load(0, x);
    // Comparisons [first, last) shifted into one word, MSB first (bit 61 - j lies in word
    // (61 - j) / 16: j 0..13 in word 3, 14..29 in 2, 30..45 in 1, 46..61 in 0).
    const auto word = [&](int first, int last) {
      auto bits = hn::Zero(d16);
      for (int j = first; j < last; ++j) {
        const auto& [dy, dx] = kNeighbours[static_cast<std::size_t>(j)];
        bits = hn::Sub(hn::ShiftLeft<1>(bits), hn::VecFromMask(d16, hn::Lt(load(dy, x + dx), centre)));
      }
      return bits;
    };
    hn::Store(word(0, 14), d16, words[3]);
    hn::Store(word(14, 30), d16, words[2]);
    hn::Store(word(30, 46), d16, words[1]);
    hn::Store(word(46, 62), d16, words[0]);
    for (int i = 0; i < N; ++i) {
      out[x + i] = (static_cast<std::uint64_t>(static_cast<std::uint16_t>(words[3][i])) << 48) |
                   (static_cast<std::uint64_t>(static_cast<std::uint16_t>(words[2][i])) << 32) |
                   (static_cast<std::uint64_t>(static_cast<std::uint16_t>(words[1][i])) << 16) |
                   static_cast<std::uint16_t>(words[0][i]);
    }
  }
  return x;
}

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
  if constexpr (sizeof(Pixel) == 1) {
    if (type == CensusType::Census9x7) x = Census9x7Bytes(rows, width, x, x1, out);
  }
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
