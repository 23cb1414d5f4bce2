#pragma once
/// @file transfers.hpp  Copies between host views (any row stride) and dense device buffers, on a
/// stream. A padded host row (a cv::Mat ROI's) is copied row by row by one 2D copy.

#include <cstdint>
#include <vector>

#include <cuda_runtime_api.h>

#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/device_buffer.hpp"
#include "backends/cuda/device_types.hpp"
#include "backends/cuda/kernels.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace cuda {

/// `host` into `buffer` (grown as needed), densely packed (stride = width).
template <typename T>
void uploadImage(ImageView<const T> host, DeviceBuffer<T>& buffer, cudaStream_t stream) {
  const std::size_t rowBytes = static_cast<std::size_t>(host.width) * sizeof(T);
  buffer.reserve(static_cast<std::size_t>(host.width) * host.height);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2DAsync(buffer.data(), rowBytes, host.data, static_cast<std::size_t>(host.stride) * sizeof(T),
                                         rowBytes, static_cast<std::size_t>(host.height), cudaMemcpyHostToDevice, stream));
}

template <typename T>
void uploadImage(ImageView<T> host, DeviceBuffer<std::remove_const_t<T>>& buffer, cudaStream_t stream) {
  uploadImage(ImageView<const std::remove_const_t<T>>(host.data, host.width, host.height, host.stride), buffer, stream);
}

/// A device image into a host view of the same size (any stride).
template <typename T>
void downloadImage(DeviceImage<const T> device, ImageView<T> host, cudaStream_t stream) {
  const std::size_t rowBytes = static_cast<std::size_t>(device.width) * sizeof(T);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2DAsync(host.data, static_cast<std::size_t>(host.stride) * sizeof(T), device.data,
                                         static_cast<std::size_t>(device.stride) * sizeof(T), rowBytes,
                                         static_cast<std::size_t>(device.height), cudaMemcpyDeviceToHost, stream));
}

template <typename T>
void uploadVector(const std::vector<T>& host, DeviceBuffer<T>& buffer, cudaStream_t stream) {
  buffer.reserve(host.empty() ? 1 : host.size());
  if (host.empty()) return;
  LIDAR_SGM_CUDA_CHECK(
      cudaMemcpyAsync(buffer.data(), host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice, stream));
}

/// LidarPoints' compressed rows: the points' pixels and disparities go up (8 bytes a point), the
/// per-pixel offsets (4 bytes a pixel: 1.9 MB for a KITTI frame) are rebuilt from them on the device.
inline void uploadLidar(const LidarPoints& lidar, DeviceBuffer<int>& pointPixels, DeviceBuffer<int>& pixelStart,
                        DeviceBuffer<int>& disparities16, cudaStream_t stream) {
  uploadVector(lidar.pointPixels(), pointPixels, stream);
  uploadVector(lidar.disparities16(), disparities16, stream);
  const int pixels = lidar.width() * lidar.height();
  pixelStart.reserve(static_cast<std::size_t>(pixels) + 1);
  lidarPixelStarts(pointPixels.data(), static_cast<int>(lidar.size()), pixels, pixelStart.data(), stream);
}

}  // namespace cuda
}  // namespace lidar_sgm
