#pragma once
/// @file device_types.hpp  Plain views of device memory that kernels take by value: images with
/// a row stride, the LiDAR points in compressed rows (LidarPoints' own layout, copied as is), the
/// LiDAR cost table, and the settings of the matching cost computed inside the path recursion.
/// No CUDA type appears here beyond the host/device markers, so host code fills them too.

#include <cstddef>
#include <cstdint>

#include "backends/common/host_device.hpp"

namespace lidar_sgm {
namespace cuda {

template <typename T>
struct DeviceImage {
  T* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;  ///< elements between rows

  LIDAR_SGM_HOST_DEVICE bool empty() const { return data == nullptr; }
  LIDAR_SGM_HOST_DEVICE T* row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride; }
  LIDAR_SGM_HOST_DEVICE T& operator()(int x, int y) const { return row(y)[x]; }
};

/// The points of LidarPoints in device memory: pixel (x, y) holds
/// disparities16[pixelStart[y * width + x] .. pixelStart[y * width + x + 1]).
struct DeviceLidar {
  const int* pixelStart = nullptr;  ///< width * height + 1 offsets
  const int* disparities16 = nullptr;
  int width = 0;
  int height = 0;
  bool empty() const { return pixelStart == nullptr; }
};

/// LidarCostTable in device memory: entries for |diff16| < size, cap beyond.
struct DeviceCostTable {
  const std::uint8_t* entries = nullptr;
  int size = 0;
  int cap = 0;
};

/// The LiDAR-gated search's windows (SearchWindows, search_windows.hpp) in device memory, dense
/// W x H: pixel i searches disparity indices [first[i], first[i] + count[i]). Empty: every pixel
/// searches the whole range.
struct DeviceWindows {
  const std::int16_t* first = nullptr;
  const std::int16_t* count = nullptr;
  LIDAR_SGM_HOST_DEVICE bool empty() const { return first == nullptr; }
};

/// A width x height x numDisparities volume in device memory, d innermost ([y][x][d]), as
/// CostVolume on the host.
template <typename T>
struct DeviceVolume {
  T* data = nullptr;
  int width = 0;
  int height = 0;
  int numDisparities = 0;
  LIDAR_SGM_HOST_DEVICE std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }
  LIDAR_SGM_HOST_DEVICE std::size_t size() const { return pixels() * numDisparities; }
  LIDAR_SGM_HOST_DEVICE T* at(int x, int y) const {
    return data + (static_cast<std::size_t>(y) * width + x) * numDisparities;
  }
};

/// Everything the matching cost C(p, d) of a frame needs (matching_cost.cuh), from which
/// cost_volume.cu stores it.
struct CostSettings {
  int width = 0;
  int height = 0;
  int numDisparities = 0;
  int minDisparity = 0;
  bool useCamera = false;  ///< C_S (or C_S3) takes part: stereo-only and fused
  bool useLidar = false;   ///< C_L takes part: LiDAR-only and fused
  // The camera cost: census strings of the left, right and (Triple-SGM) up images.
  DeviceImage<const std::uint64_t> leftCensus;
  DeviceImage<const std::uint64_t> rightCensus;
  DeviceImage<const std::uint64_t> upCensus;  ///< empty: two cameras
  int censusScale = 1;                         ///< 2 for the 31-bit centre-symmetric census
  int ratio16 = 0;                             ///< b_up / b in 1/65536 (Triple-SGM)
  // The LiDAR cost (Eq. 4).
  DeviceLidar lidar;
  DeviceCostTable table;
  // The fusion (Eq. 5): a per-pixel weight image, or alphaWeight everywhere when it is empty.
  DeviceImage<const std::uint16_t> weights;
  int alphaWeight = 0;
  bool stereoCostWithoutLidar = false;
};

}  // namespace cuda
}  // namespace lidar_sgm
