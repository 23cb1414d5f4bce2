// The backend's part of the confidence (core/confidence.hpp) on the GPU: the peak-ratio margin of
// the aggregated cost curve (one warp per pixel, as selection.cu) and the left-right difference
// (one thread per pixel), with cpu_ref/confidence_inputs.cpp's integer arithmetic. The rival S2
// runs over the window of the gated search: an entry of S outside it (kAbsentPathCost) is none.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "lidar_sgm/core/confidence.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kWarpsPerBlock = 8;

template <int VPL>
__global__ void __launch_bounds__(kWarpsPerBlock * kWarpSize)
    marginKernel(DeviceVolume<const std::uint16_t> sum, DeviceImage<const std::int16_t> bestIndex,
                 DeviceImage<std::uint8_t> margin, DeviceImage<std::uint16_t> bestCost) {
  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const std::size_t pixel =
      static_cast<std::size_t>(blockIdx.x) * kWarpsPerBlock + static_cast<std::size_t>(threadIdx.x) / kWarpSize;
  if (pixel >= sum.pixels()) return;  // the whole warp leaves together
  const int D = sum.numDisparities;
  const int x = static_cast<int>(pixel % static_cast<std::size_t>(sum.width));
  const int y = static_cast<int>(pixel / static_cast<std::size_t>(sum.width));
  const int best = bestIndex(x, y);
  if (best < 0) {
    if (lane == 0) {
      margin(x, y) = 0;
      bestCost(x, y) = 0;
    }
    return;
  }
  const int firstD = lane * VPL;
  int S[VPL];
  int laneSecond = INT_MAX;  // the lowest cost outside the winner's +-1
#pragma unroll
  for (int k = 0; k < VPL; ++k) {
    const int d = firstD + k;
    S[k] = d < D ? static_cast<int>(__ldg(sum.data + pixel * D + d)) : 0;
    if (d < D && abs(d - best) > 1 && S[k] != kAbsentPathCost) laneSecond = min(laneSecond, S[k]);
  }
  const int second = warpMin(laneSecond);
  const int first = __shfl_sync(kFullMask, pickSlot<VPL>(S, best % VPL), best / VPL);
  if (lane != 0) return;
  bestCost(x, y) = static_cast<std::uint16_t>(first);
  if (second == INT_MAX) {
    margin(x, y) = 255;  // no rival
    return;
  }
  const int value = (256 * (second - first)) / max(second, 1);
  margin(x, y) = static_cast<std::uint8_t>(min(value, 255));
}

__global__ void leftRightDifferenceKernel(DeviceImage<const std::int16_t> bestIndex,
                                          DeviceImage<const std::int16_t> rightIndex, int minDisparity,
                                          DeviceImage<std::uint8_t> difference) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= bestIndex.width || y >= bestIndex.height) return;
  const int best = bestIndex(x, y);
  const int xr = x - (minDisparity + best);
  if (best < 0 || xr < 0 || xr >= bestIndex.width || rightIndex(xr, y) < 0) {
    difference(x, y) = kNoCounterpartDifference;
    return;
  }
  difference(x, y) = static_cast<std::uint8_t>(min(abs(rightIndex(xr, y) - best), 254));
}

}  // namespace

void peakRatioMargin(DeviceVolume<const std::uint16_t> sum, DeviceImage<const std::int16_t> bestIndex,
                     DeviceImage<std::uint8_t> margin, DeviceImage<std::uint16_t> bestCost, cudaStream_t stream) {
  const unsigned blocks = static_cast<unsigned>((sum.pixels() + kWarpsPerBlock - 1) / kWarpsPerBlock);
  withSlotsPerLane(sum.numDisparities, [&](auto slots) {
    constexpr int VPL = decltype(slots)::value;
    marginKernel<VPL><<<blocks, kWarpsPerBlock * kWarpSize, 0, stream>>>(sum, bestIndex, margin, bestCost);
  });
  LIDAR_SGM_CUDA_CHECK_LAUNCH("marginKernel");
}

void leftRightDifference(DeviceImage<const std::int16_t> bestIndex, DeviceImage<const std::int16_t> rightIndex,
                         int minDisparity, DeviceImage<std::uint8_t> difference, cudaStream_t stream) {
  leftRightDifferenceKernel<<<pixelGrid(bestIndex.width, bestIndex.height), pixelBlock(), 0, stream>>>(
      bestIndex, rightIndex, minDisparity, difference);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("leftRightDifferenceKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
