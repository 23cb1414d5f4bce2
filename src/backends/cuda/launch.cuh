#pragma once
/// @file launch.cuh  Grid sizes and warp reductions shared by the kernels.

#include <climits>
#include <type_traits>

namespace lidar_sgm {
namespace cuda {

constexpr unsigned kFullMask = 0xFFFFFFFFu;
constexpr int kWarpSize = 32;

/// Blocks of 32 x 8 threads over an image, one thread per pixel.
inline dim3 pixelBlock() { return dim3(32, 8); }
inline dim3 pixelGrid(int width, int height) {
  return dim3(static_cast<unsigned>((width + 31) / 32), static_cast<unsigned>((height + 7) / 8));
}

__device__ __forceinline__ int warpMin(int value) {
  for (int offset = 16; offset > 0; offset >>= 1) value = min(value, __shfl_xor_sync(kFullMask, value, offset));
  return value;
}

__device__ __forceinline__ unsigned warpMin(unsigned value) {
  for (int offset = 16; offset > 0; offset >>= 1) value = min(value, __shfl_xor_sync(kFullMask, value, offset));
  return value;
}

/// The values a lane holds for disparities lane * VPL + k, k < VPL: VPL = the smallest power of
/// two with 32 * VPL >= D. Since D is a multiple of 16 and VPL <= 16, a lane's slots are all
/// below D or all at or above it.
template <int VPL>
__device__ __forceinline__ int pickSlot(const int (&values)[VPL], int k) {
  int v = values[0];
#pragma unroll
  for (int i = 1; i < VPL; ++i) v = i == k ? values[i] : v;
  return v;
}

/// Calls f(std::integral_constant<int, VPL>{}) with the VPL for numDisparities (16..512).
template <typename F>
void withSlotsPerLane(int numDisparities, F&& f) {
  if (numDisparities <= 32) {
    f(std::integral_constant<int, 1>{});
  } else if (numDisparities <= 64) {
    f(std::integral_constant<int, 2>{});
  } else if (numDisparities <= 128) {
    f(std::integral_constant<int, 4>{});
  } else if (numDisparities <= 256) {
    f(std::integral_constant<int, 8>{});
  } else {
    f(std::integral_constant<int, 16>{});
  }
}

}  // namespace cuda
}  // namespace lidar_sgm
