// Small SIMD helpers shared by several kernel files, for every Highway target.
// Per-target header: included once per target, hence the toggled guard instead of #pragma once.
#if defined(LIDAR_SGM_CPU_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef LIDAR_SGM_CPU_SIMD_INL_H_
#undef LIDAR_SGM_CPU_SIMD_INL_H_
#else
#define LIDAR_SGM_CPU_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace lidar_sgm {
namespace cpu {
namespace HWY_NAMESPACE {

// Up to 16 uint16 lanes: D is a multiple of 16, so every width up to 16 divides it.
using D16 = hwy::HWY_NAMESPACE::CappedTag<std::uint16_t, 16>;

// Lanes(D16()) path costs or sums from p, as uint16 (8-bit path costs promoted).
template <typename T>
HWY_INLINE hwy::HWY_NAMESPACE::Vec<D16> LoadAsU16(const T* p) {
  namespace hn = hwy::HWY_NAMESPACE;
  const D16 d16;
  if constexpr (sizeof(T) == 1) {
    return hn::PromoteTo(d16, hn::LoadU(hn::Rebind<std::uint8_t, D16>(), p));
  } else {
    return hn::LoadU(d16, p);
  }
}

#if HWY_MAX_BYTES >= 32
// The lane-wise minimum of a vector's two halves: a running minimum carried to the next narrower
// block, or the first step of a reduction.
template <class DT>
HWY_INLINE hwy::HWY_NAMESPACE::Vec<hwy::HWY_NAMESPACE::Half<DT>> MinOfHalves(DT /* d */,
                                                                          hwy::HWY_NAMESPACE::Vec<DT> v) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::Half<DT> dh;
  return hn::Min(hn::LowerHalf(dh, v), hn::UpperHalf(dh, v));
}
#endif

// The smallest of a D16 vector's lanes. Highway's MinOfLanes of a 32-byte vector of uint16 takes
// about ten shuffles and minima; halving it to 16 bytes first leaves one PHMINPOSUW (x86), and
// the winner search runs this once a pixel.
HWY_INLINE unsigned MinLaneU16(hwy::HWY_NAMESPACE::Vec<D16> v) {
  namespace hn = hwy::HWY_NAMESPACE;
#if HWY_MAX_BYTES >= 32
  return hn::GetLane(hn::MinOfLanes(hn::Half<D16>(), MinOfHalves(D16(), v)));
#else
  return hn::GetLane(hn::MinOfLanes(D16(), v));
#endif
}

// Eq. 5 on a run of cost bytes (fusion.cpp's fuseCosts stage):
// fused[i] = (w * lidar[i] + (256 - w) * stereo[i] + 128) >> 8, cpu_ref's weights and rounding;
// lidar == nullptr stands for C_L = 0 (no point near the pixel). The sum fits 16 bits because
// the weights add up to 256: at most 255 * 256 + 128. `fused` may be `stereo`.
HWY_INLINE void FuseBytes(const std::uint8_t* lidar, const std::uint8_t* stereo, std::size_t n, int alphaWeight256,
                          std::uint8_t* fused) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::CappedTag<std::uint16_t, 16> d16;
  const hn::Rebind<std::uint8_t, decltype(d16)> d8;
  const hn::Rebind<std::int16_t, decltype(d16)> di16;
  const std::size_t N = hn::Lanes(d16);
  const auto wL = hn::Set(d16, static_cast<std::uint16_t>(alphaWeight256));
  const auto wS = hn::Set(d16, static_cast<std::uint16_t>(256 - alphaWeight256));
  const auto half = hn::Set(d16, std::uint16_t{128});
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    auto weighted = hn::Add(hn::Mul(hn::PromoteTo(d16, hn::LoadU(d8, stereo + i)), wS), half);
    if (lidar != nullptr) weighted = hn::Add(weighted, hn::Mul(hn::PromoteTo(d16, hn::LoadU(d8, lidar + i)), wL));
    hn::StoreU(hn::DemoteTo(d8, hn::BitCast(di16, hn::ShiftRight<8>(weighted))), d8, fused + i);
  }
  for (; i < n; ++i) {
    const int cL = lidar != nullptr ? lidar[i] : 0;
    fused[i] = static_cast<std::uint8_t>((alphaWeight256 * cL + (256 - alphaWeight256) * stereo[i] + 128) >> 8);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace cpu
}  // namespace lidar_sgm
HWY_AFTER_NAMESPACE();

#endif  // LIDAR_SGM_CPU_SIMD_INL_H_
