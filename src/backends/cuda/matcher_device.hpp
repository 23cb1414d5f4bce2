#pragma once
// What the CUDA matcher keeps on the device between frames: its stream, the events that time
// the stages, and every buffer of a frame (grown only, like the CPU backends' buffers).

#include <array>
#include <cstdint>
#include <vector>

#include <cuda_runtime_api.h>

#include "backends/common/lidar_cost_table.hpp"
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/cuda_matcher.hpp"
#include "backends/cuda/device_buffer.hpp"
#include "backends/cuda/readback.hpp"
#include "backends/cuda/transfers.hpp"
#include "lidar_sgm/core/confidence.hpp"

namespace lidar_sgm {
namespace cuda {

// The points in time between which the stages of a frame ran, recorded on the stream.
enum Mark {
  kStart,
  kUploaded,
  kCensus,
  kLidar,
  kCosts,
  kAggregated,
  kSelected,
  kChecked,
  kFiltered,
  kConfidence,
  kDownloaded,
  kMarks
};

struct CudaMatcher::Device {
  cudaStream_t stream = nullptr;
  std::array<cudaEvent_t, kMarks> events{};
  // Recorded on the caller's stream of a device frame; `stream` waits for it (DeviceFrame::stream).
  cudaEvent_t callerInputs = nullptr;

  DeviceBuffer<std::uint8_t> images8[3];    // left, right, up (8-bit frames)
  DeviceBuffer<std::uint16_t> images16[3];  // ... (16-bit frames)
  DeviceBuffer<std::uint64_t> census[3];
  DeviceBuffer<int> pointPixels;  // LidarPoints::pointPixels(), from which pixelStart is built
  DeviceBuffer<int> pixelStart;
  DeviceBuffer<int> disparities16;
  DeviceBuffer<std::uint8_t> table;
  DeviceBuffer<std::uint16_t> weights;  // adaptive alpha only
  DeviceBuffer<std::uint8_t> coverage;
  // The gated search's windows (search_windows.cu), computed on the device from the points, and
  // the extremes of its first pass.
  DeviceBuffer<std::int16_t> windowFirst;
  DeviceBuffer<std::int16_t> windowCount;
  DeviceBuffer<std::int16_t> windowLowest;
  DeviceBuffer<std::int16_t> windowHighest;
  DeviceBuffer<std::uint8_t> matchingCost;  // C, W x H x D bytes (cost_volume.cu)
  // One L_r volume per path, in 8 bits where the frame's path costs fit (kernels.hpp), else 16;
  // only the one a frame uses is allocated.
  DeviceBuffer<std::uint8_t> pathCosts8;
  DeviceBuffer<std::uint16_t> pathCosts;
  DeviceBuffer<std::uint16_t> sum;
  DeviceBuffer<std::int16_t> rawDisparity;
  DeviceBuffer<std::int16_t> bestIndex;
  DeviceBuffer<std::int16_t> rightIndex;
  // The confidence's core part (confidence.cu) and its logistic table.
  DeviceBuffer<std::uint8_t> verticalDistance;
  DeviceBuffer<std::uint8_t> sigmoid;
  // The disparity, support, confidence and its inputs: one allocation, one copy back (readback.hpp).
  DeviceBuffer<std::uint8_t> readback;
  PinnedBuffer pinned;
  LidarCostTable hostTable;
  float tableSigma = 0;
  int tableCap = -1;
  Image<std::uint16_t> hostWeights;

  Device() {
    LIDAR_SGM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
    for (cudaEvent_t& e : events) LIDAR_SGM_CUDA_CHECK(cudaEventCreate(&e));
    // No timing: the cheapest event to record and wait for.
    LIDAR_SGM_CUDA_CHECK(cudaEventCreateWithFlags(&callerInputs, cudaEventDisableTiming));
    // The core's logistic curve, entry i at logit (i - 1024) / 64 (confidenceFromLogit256).
    std::vector<std::uint8_t> curve(2048);
    for (int i = 0; i < 2048; ++i) curve[static_cast<std::size_t>(i)] = confidenceFromLogit256(4 * (i - 1024));
    uploadVector(curve, sigmoid, stream);
    LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(stream));
  }
  ~Device() {
    for (cudaEvent_t e : events) {
      if (e != nullptr) cudaEventDestroy(e);
    }
    if (callerInputs != nullptr) cudaEventDestroy(callerInputs);
    if (stream != nullptr) cudaStreamDestroy(stream);
  }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  void mark(Mark m) { LIDAR_SGM_CUDA_CHECK(cudaEventRecord(events[m], stream)); }
  double ms(Mark from, Mark to) const {
    float value = 0;
    LIDAR_SGM_CUDA_CHECK(cudaEventElapsedTime(&value, events[from], events[to]));
    return value;
  }
};

}  // namespace cuda
}  // namespace lidar_sgm
