#pragma once
// What the host reads back after a frame (the disparity, the LiDAR support, the confidence and
// its inputs), laid out in one device allocation so that one copy brings it all, into pinned
// host memory: ten copies into pageable memory cost ten driver-staged, blocking transfers.

#include <cstddef>
#include <cstdint>

#include <cuda_runtime_api.h>

#include "backends/cuda/cuda_error.hpp"

namespace lidar_sgm {
namespace cuda {

/// Byte offsets of a W x H frame's read-back images in the one allocation (each 256-byte
/// aligned, as cudaMalloc's own). The disparity comes last: a frame whose disparity stays on the
/// device (computeOnDevice with MemorySpace::Device) copies only the bytes before it.
struct ReadbackLayout {
  std::size_t support = 0, margin = 0, bestCost = 0, difference = 0, distance = 0, texture = 0, saturated = 0,
              range = 0, confidence = 0, disparity = 0, bytes = 0;

  ReadbackLayout(int width, int height) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::size_t next = 0;
    const auto take = [&](std::size_t bytesPerPixel) {
      const std::size_t at = next;
      next += (pixels * bytesPerPixel + 255) / 256 * 256;
      return at;
    };
    support = take(1);
    margin = take(1);
    bestCost = take(sizeof(std::uint16_t));
    difference = take(1);
    distance = take(1);
    texture = take(1);
    saturated = take(1);
    range = take(1);
    confidence = take(1);
    disparity = take(sizeof(std::int16_t));
    bytes = next;
  }
};

/// Page-locked host memory that grows and is kept between frames (the read-back's target).
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  ~PinnedBuffer() {
    if (data_ != nullptr) cudaFreeHost(data_);  // never throws from a destructor
  }
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;

  /// At least `bytes`; the contents are undefined after a reallocation.
  void reserve(std::size_t bytes) {
    if (bytes <= capacity_) return;
    if (data_ != nullptr) cudaFreeHost(data_);
    data_ = nullptr;
    capacity_ = 0;
    void* p = nullptr;
    LIDAR_SGM_CUDA_CHECK(cudaMallocHost(&p, bytes));
    data_ = static_cast<std::uint8_t*>(p);
    capacity_ = bytes;
  }
  std::uint8_t* data() { return data_; }
  const std::uint8_t* data() const { return data_; }

 private:
  std::uint8_t* data_ = nullptr;
  std::size_t capacity_ = 0;
};

}  // namespace cuda
}  // namespace lidar_sgm
