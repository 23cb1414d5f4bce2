// Frames given in device memory (Matcher::computeOnDevice): the copies the core asks for, to
// validate the LiDAR samples on the host and to run the half-scale mode's resampling there.
// Every copy runs on the matcher's stream, after the caller's stream has written the inputs.
#include <cstddef>
#include <utility>

#include <cuda_runtime_api.h>

#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/cuda_matcher.hpp"
#include "backends/cuda/matcher_device.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

template <typename T>
ImageView<const T> downloaded(ImageView<const T> device, int width, int height, Image<T>& host, cudaStream_t stream) {
  host.resize(width, height);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2DAsync(host.data(), static_cast<std::size_t>(width) * sizeof(T), device.data,
                                         static_cast<std::size_t>(device.stride) * sizeof(T),
                                         static_cast<std::size_t>(width) * sizeof(T), static_cast<std::size_t>(height),
                                         cudaMemcpyDeviceToHost, stream));
  return std::as_const(host).view();
}

// A gray image in device memory, copied into the host buffer of its depth.
GrayImageView downloaded(const GrayImageView& device, Image<std::uint8_t>& host8, Image<std::uint16_t>& host16,
                         cudaStream_t stream) {
  if (device.empty()) return {};
  if (!device.gray8.empty()) return downloaded(device.gray8, device.width(), device.height(), host8, stream);
  return downloaded(device.gray16, device.width(), device.height(), host16, stream);
}

}  // namespace

void CudaMatcher::copyToHost(const DeviceFrame& frame, bool images, DeviceFrameCopy& host) {
  Device& dev = *device_;
  // The matcher's stream is non-blocking: without this wait it could read inputs the caller's
  // stream is still writing. The wait stays in the stream's order, so runOnDevice's stages,
  // queued after it, are ordered too.
  LIDAR_SGM_CUDA_CHECK(cudaEventRecord(dev.callerInputs, static_cast<cudaStream_t>(frame.stream)));
  LIDAR_SGM_CUDA_CHECK(cudaStreamWaitEvent(dev.stream, dev.callerInputs, 0));
  if (frame.lidar != nullptr && frame.lidarCount > 0) {
    host.samples.resize(frame.lidarCount);
    LIDAR_SGM_CUDA_CHECK(cudaMemcpyAsync(host.samples.data(), frame.lidar, frame.lidarCount * sizeof(LidarSample),
                                         cudaMemcpyDeviceToHost, dev.stream));
  }
  if (images) {
    host.left = downloaded(frame.left, host.left8, host.left16, dev.stream);
    host.right = downloaded(frame.right, host.right8, host.right16, dev.stream);
  }
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(dev.stream));
}

void CudaMatcher::copyToDevice(ImageView<const std::int16_t> host, ImageView<std::int16_t> device) {
  Device& dev = *device_;
  const std::size_t rowBytes = static_cast<std::size_t>(host.width) * sizeof(std::int16_t);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2DAsync(device.data, static_cast<std::size_t>(device.stride) * sizeof(std::int16_t),
                                         host.data, static_cast<std::size_t>(host.stride) * sizeof(std::int16_t),
                                         rowBytes, static_cast<std::size_t>(host.height), cudaMemcpyHostToDevice,
                                         dev.stream));
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(dev.stream));
}

}  // namespace cuda
}  // namespace lidar_sgm
