// Where the LiDAR has information, on the GPU: the support of C_L (a point in the 3x3
// neighbourhood, cpu_ref/lidar_cost.cpp) and the coverage the left-right check spares.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "backends/cuda/matching_cost.cuh"

namespace lidar_sgm {
namespace cuda {
namespace {

// A binary search per pixel: no scan, no atomics, so the offsets are the host's exactly.
__global__ void pixelStartKernel(const int* pointPixels, int count, int pixels, int* pixelStart) {
  const int p = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (p > pixels) return;
  int lo = 0;
  int hi = count;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (__ldg(pointPixels + mid) < p) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  pixelStart[p] = lo;
}

__global__ void supportKernel(DeviceLidar lidar, DeviceImage<std::uint8_t> support) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= lidar.width || y >= lidar.height) return;
  support(x, y) = lidarNeighbourhood(lidar, x, y).empty() ? 0 : 1;
}

__global__ void coverageKernel(DeviceLidar lidar, int rows, DeviceImage<std::uint8_t> coverage) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= lidar.width || y >= lidar.height) return;
  const int x0 = max(0, x - 1);
  const int x1 = min(lidar.width - 1, x + 1);
  bool covered = false;
  for (int ny = max(0, y - rows); ny <= min(lidar.height - 1, y + rows) && !covered; ++ny) {
    const int* rowStart = lidar.pixelStart + static_cast<std::size_t>(ny) * lidar.width;
    covered = __ldg(rowStart + x1 + 1) > __ldg(rowStart + x0);
  }
  coverage(x, y) = covered ? 1 : 0;
}

}  // namespace

void lidarPixelStarts(const int* pointPixels, int count, int pixels, int* pixelStart, cudaStream_t stream) {
  const int threads = 256;
  const int blocks = (pixels + 1 + threads - 1) / threads;
  pixelStartKernel<<<blocks, threads, 0, stream>>>(pointPixels, count, pixels, pixelStart);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("pixelStartKernel");
}

void lidarSupport(DeviceLidar lidar, DeviceImage<std::uint8_t> support, cudaStream_t stream) {
  supportKernel<<<pixelGrid(lidar.width, lidar.height), pixelBlock(), 0, stream>>>(lidar, support);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("supportKernel");
}

void lidarCoverage(DeviceLidar lidar, int rows, DeviceImage<std::uint8_t> coverage, cudaStream_t stream) {
  coverageKernel<<<pixelGrid(lidar.width, lidar.height), pixelBlock(), 0, stream>>>(lidar, rows, coverage);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("coverageKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
