// Median filter over valid disparities on the GPU: one thread per pixel gathers the valid values
// of its window (at most 25) and takes the lower median, as cpu_ref/median.cpp.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kMaxWindow = 25;  // 5 x 5, the largest size Parameters allows

__global__ void medianKernel(DeviceImage<const std::int16_t> in, int radius, DeviceImage<std::int16_t> out) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= in.width || y >= in.height) return;
  const std::int16_t centre = in(x, y);
  if (radius == 0 || centre == kInvalidDisparity) {
    out(x, y) = centre;  // an invalid pixel is not filled: the median removes outliers only
    return;
  }
  std::int16_t window[kMaxWindow];
  int n = 0;
  for (int ny = max(0, y - radius); ny <= min(in.height - 1, y + radius); ++ny) {
    for (int nx = max(0, x - radius); nx <= min(in.width - 1, x + radius); ++nx) {
      const std::int16_t v = in(nx, ny);
      if (v == kInvalidDisparity) continue;
      // Insertion into the sorted prefix.
      int i = n++;
      while (i > 0 && window[i - 1] > v) {
        window[i] = window[i - 1];
        --i;
      }
      window[i] = v;
    }
  }
  out(x, y) = window[(n - 1) / 2];  // lower median for even counts
}

}  // namespace

void medianFilter(DeviceImage<const std::int16_t> in, int size, DeviceImage<std::int16_t> out, cudaStream_t stream) {
  medianKernel<<<pixelGrid(in.width, in.height), pixelBlock(), 0, stream>>>(in, size / 2, out);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("medianKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
