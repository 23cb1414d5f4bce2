// The sum over paths (Eq. 2's S) and the winner-takes-all selection on the GPU: one warp per
// pixel, VPL disparities per lane. The winner is the minimum of the keys (S << 16) | d, so the
// first minimum wins ties as in cpu_ref/selection.cpp; uniqueness and the parabola use the same
// integer arithmetic. The L_r volumes hold 8 or 16 bits a path cost (aggregation.cu). With the
// gated search, an entry outside the pixel's window is absent in every path (absentPathCost,
// aggregation.cu) and kAbsentPathCost in S: above every real key, never a rival, and a winner
// next to it keeps its integer disparity (cpu_ref/gated_selection.cpp).
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kWarpsPerBlock = 8;

/// Rounded (half away from zero) integer division, as cpu_ref's roundedDivide.
__device__ __forceinline__ int roundedDivide(int numerator, int denominator) {
  const int half = denominator / 2;
  return numerator >= 0 ? (numerator + half) / denominator : -((-numerator + half) / denominator);
}

template <int VPL>
__device__ __forceinline__ void loadSlots(const std::uint16_t* in, int (&values)[VPL]) {
#pragma unroll
  for (int k = 0; k < VPL; ++k) values[k] = __ldg(in + k);
}

/// 8-bit path costs: VPL >= 4 as 4-byte words (aligned: D is a multiple of 16, firstD of VPL).
template <int VPL>
__device__ __forceinline__ void loadSlots(const std::uint8_t* in, int (&values)[VPL]) {
  if constexpr (VPL < 4) {
#pragma unroll
    for (int k = 0; k < VPL; ++k) values[k] = __ldg(in + k);
  } else {
#pragma unroll
    for (int k = 0; k < VPL; k += 4) {
      const unsigned word = __ldg(reinterpret_cast<const unsigned*>(in + k));
#pragma unroll
      for (int b = 0; b < 4; ++b) values[k + b] = static_cast<int>((word >> (8 * b)) & 0xFFu);
    }
  }
}

template <int VPL, typename PathT>
__global__ void __launch_bounds__(kWarpsPerBlock * kWarpSize)
    selectKernel(DeviceVolume<const PathT> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                 int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                 DeviceImage<std::int16_t> bestIndex) {
  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const std::size_t pixel =
      static_cast<std::size_t>(blockIdx.x) * kWarpsPerBlock + static_cast<std::size_t>(threadIdx.x) / kWarpSize;
  if (pixel >= pathCosts.pixels()) return;  // the whole warp leaves together
  const int D = pathCosts.numDisparities;
  const int x = static_cast<int>(pixel % static_cast<std::size_t>(pathCosts.width));
  const int y = static_cast<int>(pixel / static_cast<std::size_t>(pathCosts.width));
  const int firstD = lane * VPL;
  const bool active = firstD < D;

  int S[VPL];
#pragma unroll
  for (int k = 0; k < VPL; ++k) S[k] = 0;
  if (active) {
    bool absent[VPL] = {};
    for (int r = 0; r < numPaths; ++r) {
      int L[VPL];
      loadSlots<VPL>(pathCosts.data + static_cast<std::size_t>(r) * pathCosts.size() + pixel * D + firstD, L);
#pragma unroll
      for (int k = 0; k < VPL; ++k) {
        if (r == 0) absent[k] = L[k] == absentPathCost<PathT>();  // outside the window: so in every path
        S[k] += L[k];  // <= 8 * (255 + 4000): no 16-bit overflow
      }
    }
#pragma unroll
    for (int k = 0; k < VPL; ++k) {
      if (absent[k]) S[k] = kAbsentPathCost;
    }
    if (sum.data != nullptr) {
      std::uint16_t* out = sum.data + pixel * D + firstD;
#pragma unroll
      for (int k = 0; k < VPL; ++k) out[k] = static_cast<std::uint16_t>(S[k]);
    }
  }
  if (disparity16.empty()) return;

  unsigned laneKey = 0xFFFFFFFFu;
  if (active) {
#pragma unroll
    for (int k = 0; k < VPL; ++k) laneKey = min(laneKey, (static_cast<unsigned>(S[k]) << 16) | (firstD + k));
  }
  const unsigned key = warpMin(laneKey);
  const int best = static_cast<int>(key & 0xFFFFu);
  const int bestCost = static_cast<int>(key >> 16);

  bool unique = true;
  if (uniquenessRatio > 0) {
    // OpenCV's rule: every cost farther than 1 px from the winner must exceed it by the ratio.
    bool rival = false;
    if (active) {
#pragma unroll
      for (int k = 0; k < VPL; ++k) {
        const int d = firstD + k;
        if (S[k] != kAbsentPathCost && abs(d - best) > 1 && S[k] * (100 - uniquenessRatio) < bestCost * 100) {
          rival = true;
        }
      }
    }
    unique = !__any_sync(kFullMask, rival);
  }
  // The neighbours of the winner for the parabola, from the lanes that hold them.
  const int before = best > 0 ? best - 1 : best;
  const int after = best + 1 < D ? best + 1 : best;
  const int costBefore = __shfl_sync(kFullMask, pickSlot<VPL>(S, before % VPL), before / VPL);
  const int costAfter = __shfl_sync(kFullMask, pickSlot<VPL>(S, after % VPL), after / VPL);
  if (lane != 0) return;
  if (!unique) {
    disparity16(x, y) = kInvalidDisparity;
    bestIndex(x, y) = -1;
    return;
  }
  int offset16 = 0;
  if (subpixel && best > 0 && best < D - 1 && costBefore != kAbsentPathCost && costAfter != kAbsentPathCost) {
    // Vertex of the parabola through (best-1, best, best+1), both in the window: (S- - S+) / (2 (S- + S+ - 2 S)).
    const int curvature = costBefore + costAfter - 2 * bestCost;
    if (curvature > 0) offset16 = roundedDivide((costBefore - costAfter) * kDisparityScale, 2 * curvature);
  }
  disparity16(x, y) = static_cast<std::int16_t>((minDisparity + best) * kDisparityScale + offset16);
  bestIndex(x, y) = static_cast<std::int16_t>(best);
}

template <typename PathT>
void launchSelection(DeviceVolume<const PathT> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                     int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                     DeviceImage<std::int16_t> bestIndex, cudaStream_t stream) {
  const unsigned blocks = static_cast<unsigned>((pathCosts.pixels() + kWarpsPerBlock - 1) / kWarpsPerBlock);
  withSlotsPerLane(pathCosts.numDisparities, [&](auto slots) {
    constexpr int VPL = decltype(slots)::value;
    selectKernel<VPL, PathT><<<blocks, kWarpsPerBlock * kWarpSize, 0, stream>>>(
        pathCosts, numPaths, sum, minDisparity, uniquenessRatio, subpixel, disparity16, bestIndex);
  });
  LIDAR_SGM_CUDA_CHECK_LAUNCH("selectKernel");
}

}  // namespace

void selectDisparity(DeviceVolume<const std::uint8_t> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                     int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                     DeviceImage<std::int16_t> bestIndex, cudaStream_t stream) {
  launchSelection(pathCosts, numPaths, sum, minDisparity, uniquenessRatio, subpixel, disparity16, bestIndex, stream);
}

void selectDisparity(DeviceVolume<const std::uint16_t> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                     int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                     DeviceImage<std::int16_t> bestIndex, cudaStream_t stream) {
  launchSelection(pathCosts, numPaths, sum, minDisparity, uniquenessRatio, subpixel, disparity16, bestIndex, stream);
}

}  // namespace cuda
}  // namespace lidar_sgm
