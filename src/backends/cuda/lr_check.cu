// Left-right consistency on the GPU: the right view's winners read diagonally from the left
// volume S (as cpu_ref/lr_check.cpp and OpenCV's SGBM), and the check itself.
//
// rightDisparityIndex: a block owns a tile of kTile right pixels of one row. Right pixel xr
// sees left pixel x = xr + minDisparity + d at disparity index d, so for each left pixel x the
// tile's candidates are a contiguous run of d: a warp reads that run (coalesced) and keeps the
// minimum key (S << 16) | d per right pixel with a shared-memory atomicMin. The smallest key is
// the lowest cost with the smallest d: cpu_ref's first minimum. An entry outside its left pixel's
// window (kAbsentPathCost, the gated search) is no candidate; a right pixel without any gets -1
// (cpu_ref/gated_lr_check.cpp).
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kTile = 64;
constexpr int kWarpsPerBlock = 4;

__global__ void __launch_bounds__(kWarpsPerBlock * kWarpSize)
    rightIndexKernel(DeviceVolume<const std::uint16_t> sum, int minDisparity, DeviceImage<std::int16_t> rightIndex) {
  __shared__ unsigned keys[kTile];
  const int width = sum.width;
  const int D = sum.numDisparities;
  const int y = static_cast<int>(blockIdx.y);
  const int xr0 = static_cast<int>(blockIdx.x) * kTile;
  for (int i = static_cast<int>(threadIdx.x); i < kTile; i += static_cast<int>(blockDim.x)) keys[i] = 0xFFFFFFFFu;
  __syncthreads();

  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const int warp = static_cast<int>(threadIdx.x) / kWarpSize;
  // Left pixels that some right pixel of the tile sees: x = xr + minDisparity + d.
  const int xBegin = max(0, xr0 + minDisparity);
  const int xEnd = min(width, xr0 + kTile + minDisparity + D - 1);
  for (int x = xBegin + warp; x < xEnd; x += kWarpsPerBlock) {
    // d such that xr = x - minDisparity - d lies in [xr0, xr0 + kTile) and in the image.
    const int dLow = max(0, x - minDisparity - (xr0 + kTile - 1));
    const int dHigh = min(D - 1, x - minDisparity - xr0);
    const std::uint16_t* S = sum.at(x, y);
    for (int d = dLow + lane; d <= dHigh; d += kWarpSize) {
      const int xr = x - minDisparity - d;
      const unsigned cost = __ldg(S + d);
      if (xr >= width || cost == kAbsentPathCost) continue;
      atomicMin(&keys[xr - xr0], (cost << 16) | static_cast<unsigned>(d));
    }
  }
  __syncthreads();
  for (int i = static_cast<int>(threadIdx.x); i < kTile; i += static_cast<int>(blockDim.x)) {
    const int xr = xr0 + i;
    if (xr >= width) continue;
    rightIndex(xr, y) = keys[i] == 0xFFFFFFFFu ? std::int16_t{-1} : static_cast<std::int16_t>(keys[i] & 0xFFFFu);
  }
}

__global__ void leftRightCheckKernel(DeviceImage<std::int16_t> disparity16, DeviceImage<std::int16_t> bestIndex,
                                     DeviceImage<const std::int16_t> rightIndex, DeviceImage<const std::uint8_t> support,
                                     int minDisparity, int disp12MaxDiff, bool keepNoCounterpart) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= rightIndex.width || y >= rightIndex.height) return;
  const int best = bestIndex(x, y);
  if (best < 0) return;
  bool keep = true;
  const int xr = x - (minDisparity + best);
  if (xr < 0 || xr >= rightIndex.width) {
    keep = keepNoCounterpart;  // the right camera cannot see it: nothing to compare
  } else if (!support.empty() && support(x, y) != 0) {
    keep = true;  // a LiDAR point measured it
  } else {
    const int right = rightIndex(xr, y);
    keep = right >= 0 && abs(right - best) <= disp12MaxDiff;
  }
  if (!keep) {
    disparity16(x, y) = kInvalidDisparity;
    bestIndex(x, y) = -1;
  }
}

}  // namespace

void rightDisparityIndex(DeviceVolume<const std::uint16_t> sum, int minDisparity,
                         DeviceImage<std::int16_t> rightIndex, cudaStream_t stream) {
  const dim3 grid(static_cast<unsigned>((sum.width + kTile - 1) / kTile), static_cast<unsigned>(sum.height));
  rightIndexKernel<<<grid, kWarpsPerBlock * kWarpSize, 0, stream>>>(sum, minDisparity, rightIndex);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("rightIndexKernel");
}

void leftRightCheck(DeviceImage<std::int16_t> disparity16, DeviceImage<std::int16_t> bestIndex,
                    DeviceImage<const std::int16_t> rightIndex, DeviceImage<const std::uint8_t> support,
                    int minDisparity, int disp12MaxDiff, bool keepNoCounterpart, cudaStream_t stream) {
  leftRightCheckKernel<<<pixelGrid(rightIndex.width, rightIndex.height), pixelBlock(), 0, stream>>>(
      disparity16, bestIndex, rightIndex, support, minDisparity, disp12MaxDiff, keepNoCounterpart);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("leftRightCheckKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
