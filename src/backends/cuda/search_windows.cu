// The LiDAR gate's search windows on the GPU (lidar_search_windows.hpp), from the points already
// on the device: no window is computed on the host or uploaded. The same two passes as the host's
// and the same arithmetic (search_window_rule.hpp), so the windows are the host's bit for bit:
// the extremes of each pixel's points over +-1 column, then over +-rows rows, then the window.
#include "backends/common/search_window_rule.hpp"
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"

namespace lidar_sgm {
namespace cuda {
namespace {

// Pass 1: the points of pixels x - 1 .. x + 1 of row y are contiguous (LidarPoints' rows).
__global__ void extremesKernel(DeviceLidar lidar, DeviceImage<std::int16_t> lowest, DeviceImage<std::int16_t> highest) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= lidar.width || y >= lidar.height) return;
  const int* rowStart = lidar.pixelStart + static_cast<std::size_t>(y) * lidar.width;
  const int begin = __ldg(rowStart + max(0, x - 1));
  const int end = __ldg(rowStart + min(lidar.width - 1, x + 1) + 1);
  int low = kSearchNoLowest;
  int high = kSearchNoHighest;
  for (int i = begin; i < end; ++i) {
    const int value = searchClamp16(__ldg(lidar.disparities16 + i));
    low = min(low, value);
    high = max(high, value);
  }
  lowest(x, y) = static_cast<std::int16_t>(low);
  highest(x, y) = static_cast<std::int16_t>(high);
}

// Pass 2: the extremes over +-rows rows, then the pixel's window.
__global__ void windowsKernel(DeviceImage<const std::int16_t> lowest, DeviceImage<const std::int16_t> highest,
                              int minDisparity, int numDisparities, int rows, int margin,
                              DeviceImage<std::int16_t> first, DeviceImage<std::int16_t> count) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= lowest.width || y >= lowest.height) return;
  int low = kSearchNoLowest;
  int high = kSearchNoHighest;
  for (int ny = max(0, y - rows); ny <= min(lowest.height - 1, y + rows); ++ny) {
    low = min(low, static_cast<int>(__ldg(lowest.row(ny) + x)));
    high = max(high, static_cast<int>(__ldg(highest.row(ny) + x)));
  }
  int f = 0;
  int c = 0;
  searchWindowOf(low, high, minDisparity, numDisparities, margin, f, c);
  first(x, y) = static_cast<std::int16_t>(f);
  count(x, y) = static_cast<std::int16_t>(c);
}

}  // namespace

void lidarSearchWindows(DeviceLidar lidar, int minDisparity, int numDisparities, int rows, int margin,
                        DeviceImage<std::int16_t> lowest, DeviceImage<std::int16_t> highest,
                        DeviceImage<std::int16_t> first, DeviceImage<std::int16_t> count, cudaStream_t stream) {
  const dim3 grid = pixelGrid(lidar.width, lidar.height);
  extremesKernel<<<grid, pixelBlock(), 0, stream>>>(lidar, lowest, highest);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("extremesKernel");
  const DeviceImage<const std::int16_t> lowestIn{lowest.data, lowest.width, lowest.height, lowest.stride};
  const DeviceImage<const std::int16_t> highestIn{highest.data, highest.width, highest.height, highest.stride};
  windowsKernel<<<grid, pixelBlock(), 0, stream>>>(lowestIn, highestIn, minDisparity, numDisparities, rows, margin,
                                                   first, count);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("windowsKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
