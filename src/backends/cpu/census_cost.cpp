// Stereo matching cost C_S, fast CPU backend: Hamming distances vectorised over disparities.
// The right census row is stored as byte planes in reverse column order, so that for a left
// pixel the right pixels x - minDisparity - d of consecutive d are consecutive bytes. Each of
// the census string's bytes then costs one XOR and a 4-bit-table population count per 32
// disparities (AVX2; 16 with SSE4/NEON), summed into the cost bytes directly.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "backends/cpu/census_cost.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_stages.hpp"
#include "backends/cpu/parallel.hpp"

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// How a pixel's C_S leaves the kernel: as it is, or fused (Eq. 5) with the pixel's C_L, or with
// C_L = 0 where no LiDAR point is near.
enum class Fusion { None, WithLidar, ZeroLidar };

// Eq. 5 on a vector of cost bytes, in 16-bit halves: (w * C_L + (256 - w) * C_S + 128) >> 8, as
// simd-inl.h's FuseBytes, but on registers: fusing a block just computed avoids storing it and reading it
// back (a store-to-load round trip per 16 bytes).
template <class DU8>
HWY_INLINE hn::Vec<DU8> FuseVector(DU8 d, hn::Vec<DU8> stereo, hn::Vec<DU8> lidar, bool withLidar, int alphaWeight256) {
#if HWY_TARGET == HWY_SCALAR  // one lane, no halves
  const int cL = withLidar ? hn::GetLane(lidar) : 0;
  return hn::Set(d, static_cast<std::uint8_t>((alphaWeight256 * cL + (256 - alphaWeight256) * hn::GetLane(stereo) + 128) >> 8));
#else
  const hn::Half<DU8> dh;
  const hn::Rebind<std::uint16_t, decltype(dh)> d16;
  const hn::Rebind<std::int16_t, decltype(dh)> di16;
  const auto wL = hn::Set(d16, static_cast<std::uint16_t>(alphaWeight256));
  const auto wS = hn::Set(d16, static_cast<std::uint16_t>(256 - alphaWeight256));
  const auto half = hn::Set(d16, std::uint16_t{128});
  const auto fuseHalf = [&](auto s8, auto l8) {
    auto weighted = hn::Add(hn::Mul(hn::PromoteTo(d16, s8), wS), half);
    if (withLidar) weighted = hn::Add(weighted, hn::Mul(hn::PromoteTo(d16, l8), wL));
    return hn::DemoteTo(dh, hn::BitCast(di16, hn::ShiftRight<8>(weighted)));
  };
  const auto lo = fuseHalf(hn::LowerHalf(dh, stereo), hn::LowerHalf(dh, lidar));
  const auto hi = fuseHalf(hn::UpperHalf(dh, stereo), hn::UpperHalf(dh, lidar));
  return hn::Combine(d, hi, lo);
#endif
}

// One pixel's C_S for disparities [i0, i0 + n): per byte of the census string, XOR with the right
// pixels' bytes and a 4-bit-table population count, summed. The left byte broadcasts are made
// once per pixel and the loop over the bytes is unrolled, with two accumulators against one long
// add chain. Disparities outside [dBegin, dEnd) have no right counterpart and cost
// kNoCounterpartCensusCost. Then the fusion, if any, while the block is in registers.
template <int kBytes, Fusion kFusion, class DU8>
HWY_INLINE void HammingPixel(DU8 d, std::uint64_t left, const std::uint8_t* planes, std::size_t planeStride, int i0,
                             int n, int dBegin, int dEnd, const std::uint8_t* lidar, int alphaWeight256,
                             std::uint8_t* out) {
  using V = hn::Vec<DU8>;
  V lb[kBytes];
  for (int k = 0; k < kBytes; ++k) lb[k] = hn::Set(d, static_cast<std::uint8_t>(left >> (8 * k)));
  const V noCounterpart = hn::Set(d, static_cast<std::uint8_t>(kNoCounterpartCensusCost));
  const int N = static_cast<int>(hn::Lanes(d));
  for (int i = i0; i < i0 + n; i += N) {
    V sumEven = hn::Zero(d);
    V sumOdd = hn::Zero(d);
    for (int k = 0; k < kBytes; ++k) {
      const V x = hn::Xor(lb[k], hn::LoadU(d, planes + static_cast<std::size_t>(k) * planeStride + i));
      const V count = hn::PopulationCount(x);
      if (k % 2 == 0) {
        sumEven = hn::Add(sumEven, count);
      } else {
        sumOdd = hn::Add(sumOdd, count);
      }
    }
    V sum = hn::Add(sumEven, sumOdd);
    // The centre-symmetric string has half the bits (4 bytes); doubling keeps both types in [0, 62].
    if (kBytes == 4) sum = hn::Add(sum, sum);
    if (i < dBegin || i + N > dEnd) {
      const auto inside = hn::AndNot(hn::FirstN(d, static_cast<std::size_t>(std::clamp(dBegin - i, 0, N))),
                                     hn::FirstN(d, static_cast<std::size_t>(std::clamp(dEnd - i, 0, N))));
      sum = hn::IfThenElse(inside, sum, noCounterpart);
    }
    if (kFusion == Fusion::WithLidar) {
      sum = FuseVector(d, sum, hn::LoadU(d, lidar + i), true, alphaWeight256);
    } else if (kFusion == Fusion::ZeroLidar) {
      sum = FuseVector(d, sum, sum, false, alphaWeight256);
    }
    hn::StoreU(sum, d, out + (i - i0));
  }
}

// The costs of disparity indices [first, first + count) (count a multiple of 16) into out[0 ..
// count): the whole range, or a gated pixel's window. Whole vectors of the target (64 disparities
// a step with AVX-512, 32 with AVX2), then at most one of 32 (AVX-512), then 16: a gated window of
// 32 (the usual one: its points' span plus the margins, rounded up to 16) is one step, not two;
// each step's cost is mostly the census bytes' broadcasts and loads, whatever its width.
template <int kBytes, Fusion kFusion>
HWY_INLINE void CostPixel(std::uint64_t left, const std::uint8_t* planes, std::size_t planeStride, int first,
                          int count, int dBegin, int dEnd, const std::uint8_t* lidar, int alphaWeight256,
                          std::uint8_t* out) {
  const hn::CappedTag<std::uint8_t, 64> dWide;
  const hn::CappedTag<std::uint8_t, 32> d32;
  const hn::CappedTag<std::uint8_t, 16> d16;
  const int N = static_cast<int>(hn::Lanes(dWide));
  int done = count / N * N;
  HammingPixel<kBytes, kFusion>(dWide, left, planes, planeStride, first, done, dBegin, dEnd, lidar, alphaWeight256,
                                out);
  const int N32 = static_cast<int>(hn::Lanes(d32));
  if (N32 < N && count - done >= N32) {
    HammingPixel<kBytes, kFusion>(d32, left, planes, planeStride, first + done, N32, dBegin, dEnd, lidar,
                                  alphaWeight256, out + done);
    done += N32;
  }
  if (done < count) {
    HammingPixel<kBytes, kFusion>(d16, left, planes, planeStride, first + done, count - done, dBegin, dEnd, lidar,
                                  alphaWeight256, out + done);
  }
}

// With `fusion` set, Eq. 5 is applied to each pixel's C_S at once (see censusCostFusedRow).
template <int kBytes>
void CensusCostRowBytes(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride,
                        int pad, int width, int x0, int x1, int minDisparity, int D, const CostFusion* fusion,
                        std::uint8_t* cost, const std::int16_t* windowFirst, const std::int16_t* windowCount,
                        const std::uint32_t* costOffset) {
  for (int x = x0; x < x1; ++x) {
    const int first = windowFirst == nullptr ? 0 : windowFirst[x];
    const int count = windowFirst == nullptr ? D : windowCount[x];
    // Where the window's first cost goes: in the whole range's layout, or packed (RowWindows).
    std::uint8_t* c = costOffset != nullptr ? cost + costOffset[x] : cost + static_cast<std::size_t>(x - x0) * D + first;
    // Plane index of d = 0: the right pixel xr = x - minDisparity sits at width - 1 - xr.
    const std::uint8_t* planes = rightPlanes + pad + (width - 1 - x + minDisparity);
    // Disparities whose right pixel lies inside the image: [dBegin, dEnd).
    const int dBegin = std::clamp(x - minDisparity - width + 1, 0, D);
    const int dEnd = std::clamp(x - minDisparity + 1, dBegin, D);
    if (fusion == nullptr || (fusion->touched[x] == 0 && fusion->stereoCostWithoutLidar)) {
      CostPixel<kBytes, Fusion::None>(leftRow[x], planes, planeStride, first, count, dBegin, dEnd, nullptr, 0, c);
      continue;
    }
    const int weight = fusion->weights != nullptr ? fusion->weights[x] : fusion->alphaWeight256;
    if (fusion->touched[x] != 0) {
      CostPixel<kBytes, Fusion::WithLidar>(leftRow[x], planes, planeStride, first, count, dBegin, dEnd,
                                           fusion->lidar + static_cast<std::size_t>(x - x0) * D, weight, c);
    } else {
      CostPixel<kBytes, Fusion::ZeroLidar>(leftRow[x], planes, planeStride, first, count, dBegin, dEnd, nullptr,
                                           weight, c);
    }
  }
}

// The byte planes of census strings xr0 .. xr1-1 (censusPlanes below): plane k at index
// pad + width - 1 - xr holds byte k of string xr. Sixteen strings at a time as an 8 x 16 byte
// transpose in 16-byte vectors: each vector's two strings interleaved byte by byte, an 8 x 8
// transpose of those byte pairs, then each plane's 16 bytes reversed into the planes' reverse
// column order; the rest one string at a time.
void CensusPlanesImpl(const std::uint64_t* row, int width, int pad, int xr0, int xr1, std::uint8_t* planes,
                      std::size_t planeStride) {
  int xr = xr0;
#if HWY_TARGET != HWY_SCALAR
  const hn::Full128<std::uint8_t> d8;
  const hn::Full128<std::uint16_t> d16;
  const hn::Full128<std::uint32_t> d32;
  const hn::Full128<std::uint64_t> d64;
  // Bytes of strings s, s + 1 as [s.0, (s+1).0, s.1, (s+1).1, ...].
  alignas(16) static constexpr std::uint8_t kPairs[16] = {0, 8, 1, 9, 2, 10, 3, 11, 4, 12, 5, 13, 6, 14, 7, 15};
  alignas(16) static constexpr std::uint8_t kReverse[16] = {15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0};
  const auto pairs = hn::Load(d8, kPairs);
  const auto reverse = hn::Load(d8, kReverse);
  for (; xr + 16 <= xr1; xr += 16) {
    hn::Vec<decltype(d16)> v[8];
    for (int i = 0; i < 8; ++i) {
      // Lane k of v[i]: byte k of strings xr + 2i and xr + 2i + 1.
      v[i] = hn::BitCast(d16, hn::TableLookupBytes(hn::LoadU(d8, reinterpret_cast<const std::uint8_t*>(row + xr + 2 * i)),
                                                   pairs));
    }
    // 8 x 8 transpose of the 16-bit lanes: afterwards lane i of t[k] is lane k of v[i].
    hn::Vec<decltype(d16)> a[8];
    for (int i = 0; i < 4; ++i) {
      a[2 * i] = hn::InterleaveLower(d16, v[2 * i], v[2 * i + 1]);
      a[2 * i + 1] = hn::InterleaveUpper(d16, v[2 * i], v[2 * i + 1]);
    }
    hn::Vec<decltype(d32)> b[8];
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const auto lo = hn::BitCast(d32, a[4 * i + j]);
        const auto hi = hn::BitCast(d32, a[4 * i + 2 + j]);
        b[4 * i + 2 * j] = hn::InterleaveLower(d32, lo, hi);
        b[4 * i + 2 * j + 1] = hn::InterleaveUpper(d32, lo, hi);
      }
    }
    for (int k = 0; k < 4; ++k) {
      const auto lo = hn::BitCast(d64, b[k]);
      const auto hi = hn::BitCast(d64, b[4 + k]);
      const int k0 = 2 * k;  // b[k] and b[4 + k] hold bytes 2k and 2k + 1 of the strings
      const auto planeLow = hn::BitCast(d8, hn::InterleaveLower(d64, lo, hi));
      const auto planeHigh = hn::BitCast(d8, hn::InterleaveUpper(d64, lo, hi));
      const std::size_t at = static_cast<std::size_t>(pad + width - 1 - (xr + 15));
      hn::StoreU(hn::TableLookupBytes(planeLow, reverse), d8, planes + static_cast<std::size_t>(k0) * planeStride + at);
      hn::StoreU(hn::TableLookupBytes(planeHigh, reverse), d8,
                 planes + static_cast<std::size_t>(k0 + 1) * planeStride + at);
    }
  }
#endif
  for (; xr < xr1; ++xr) {
    for (int k = 0; k < 8; ++k) {
      planes[static_cast<std::size_t>(k) * planeStride + static_cast<std::size_t>(pad + width - 1 - xr)] =
          static_cast<std::uint8_t>(row[xr] >> (8 * k));
    }
  }
}

void CensusCostRowImpl(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride,
                       int pad, int bytes, int width, int x0, int x1, int minDisparity, int D, const CostFusion* fusion,
                       std::uint8_t* cost, const std::int16_t* windowFirst, const std::int16_t* windowCount,
                       const std::uint32_t* costOffset) {
  if (bytes == 8) {
    CensusCostRowBytes<8>(leftRow, rightPlanes, planeStride, pad, width, x0, x1, minDisparity, D, fusion, cost,
                          windowFirst, windowCount, costOffset);
  } else {
    CensusCostRowBytes<4>(leftRow, rightPlanes, planeStride, pad, width, x0, x1, minDisparity, D, fusion, cost,
                          windowFirst, windowCount, costOffset);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lidar_sgm {
namespace cpu {

HWY_EXPORT(CensusCostRowImpl);
HWY_EXPORT(CensusPlanesImpl);

int censusPlanePad(int minDisparity, int numDisparities) {
  // Loads reach from plane index minDisparity to width + minDisparity + D + 32 (a vector past).
  return std::abs(minDisparity) + numDisparities + 64;
}

void censusPlanes(const std::uint64_t* row, int width, int pad, int xr0, int xr1, std::uint8_t* planes,
                  std::size_t planeStride) {
  HWY_DYNAMIC_DISPATCH(CensusPlanesImpl)(row, width, pad, xr0, xr1, planes, planeStride);
}

void censusPlanes(const std::uint64_t* row, int width, int pad, std::uint8_t* planes, std::size_t planeStride) {
  for (int k = 0; k < 8; ++k) {
    std::uint8_t* plane = planes + static_cast<std::size_t>(k) * planeStride;
    std::memset(plane, 0, static_cast<std::size_t>(pad));
    std::memset(plane + pad + width, 0, planeStride - pad - static_cast<std::size_t>(width));
  }
  censusPlanes(row, width, pad, 0, width, planes, planeStride);
}

void censusCostRow(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride, int pad,
                   CensusType type, int width, int x0, int x1, int minDisparity, int numDisparities,
                   std::uint8_t* cost, RowWindows windows) {
  const int bytes = type == CensusType::Census9x7 ? 8 : 4;  // 62 or 31 bits
  HWY_DYNAMIC_DISPATCH(CensusCostRowImpl)(leftRow, rightPlanes, planeStride, pad, bytes, width, x0, x1, minDisparity,
                                          numDisparities, nullptr, cost, windows.first, windows.count,
                                          windows.costOffset);
}

void censusCostFusedRow(const std::uint64_t* leftRow, const std::uint8_t* rightPlanes, std::size_t planeStride,
                        int pad, CensusType type, int width, int x0, int x1, int minDisparity, int numDisparities,
                        const std::uint8_t* lidar, const std::uint8_t* touched, const std::uint16_t* weights,
                        int alphaWeight256, bool stereoCostWithoutLidar, std::uint8_t* cost, RowWindows windows) {
  const int bytes = type == CensusType::Census9x7 ? 8 : 4;
  const CostFusion fusion{lidar, touched, weights, alphaWeight256, stereoCostWithoutLidar};
  HWY_DYNAMIC_DISPATCH(CensusCostRowImpl)(leftRow, rightPlanes, planeStride, pad, bytes, width, x0, x1, minDisparity,
                                          numDisparities, &fusion, cost, windows.first, windows.count,
                                          windows.costOffset);
}

void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost, int threads) {
  const int width = leftCensus.width;
  const int pad = censusPlanePad(minDisparity, cost.numDisparities());
  const std::size_t planeStride = static_cast<std::size_t>(width) + 2 * static_cast<std::size_t>(pad);
  parallelRanges(leftCensus.height, threads, [&](int y0, int y1) {
    std::vector<std::uint8_t> planes(8 * planeStride);
    for (int y = y0; y < y1; ++y) {
      censusPlanes(rightCensus.row(y), width, pad, planes.data(), planeStride);
      censusCostRow(leftCensus.row(y), planes.data(), planeStride, pad, type, width, 0, width, minDisparity,
                    cost.numDisparities(), cost.at(0, y));
    }
  });
}

}  // namespace cpu
}  // namespace lidar_sgm
#endif  // HWY_ONCE
