// Census transform on the GPU: one thread per pixel, the comparisons of cpu_ref/census.cpp in
// the same order (MSB first, window raster order), the window clamped at the border.
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "backends/cuda/cuda_error.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kHalfWidth = 4;   // 9 columns
constexpr int kHalfHeight = 3;  // 7 rows

template <typename Pixel>
__device__ __forceinline__ Pixel clampedAt(DeviceImage<const Pixel> image, int x, int y) {
  x = min(max(x, 0), image.width - 1);
  y = min(max(y, 0), image.height - 1);
  return __ldg(image.row(y) + x);
}

template <typename Pixel>
__global__ void censusKernel(DeviceImage<const Pixel> image, bool centreSymmetric, DeviceImage<std::uint64_t> census) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= image.width || y >= image.height) return;
  std::uint64_t bits = 0;
  if (!centreSymmetric) {
    const Pixel centre = __ldg(image.row(y) + x);
    for (int dy = -kHalfHeight; dy <= kHalfHeight; ++dy) {
      for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
        if (dx == 0 && dy == 0) continue;
        bits = (bits << 1) | (clampedAt(image, x + dx, y + dy) < centre ? 1u : 0u);
      }
    }
  } else {
    // Each pixel of the window's first half against its mirror about the centre.
    for (int dy = -kHalfHeight; dy <= 0; ++dy) {
      for (int dx = -kHalfWidth; dx <= kHalfWidth; ++dx) {
        if (dy == 0 && dx >= 0) break;
        bits = (bits << 1) | (clampedAt(image, x + dx, y + dy) < clampedAt(image, x - dx, y - dy) ? 1u : 0u);
      }
    }
  }
  census(x, y) = bits;
}

template <typename Pixel>
void launchCensus(DeviceImage<const Pixel> image, CensusType type, DeviceImage<std::uint64_t> census,
                  cudaStream_t stream) {
  censusKernel<Pixel><<<pixelGrid(image.width, image.height), pixelBlock(), 0, stream>>>(
      image, type == CensusType::CenterSymmetric9x7, census);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("censusKernel");
}

}  // namespace

void censusTransform(DeviceImage<const std::uint8_t> image, CensusType type, DeviceImage<std::uint64_t> census,
                     cudaStream_t stream) {
  launchCensus(image, type, census, stream);
}

void censusTransform(DeviceImage<const std::uint16_t> image, CensusType type, DeviceImage<std::uint64_t> census,
                     cudaStream_t stream) {
  launchCensus(image, type, census, stream);
}

}  // namespace cuda
}  // namespace lidar_sgm
