#pragma once
// The CUDA backend's matcher: uploads a frame, runs the stages of kernels.hpp on one stream and
// downloads the disparity and what the core needs besides it (support, confidence inputs).

#include <cstdint>
#include <memory>
#include <string>

#include "core/backend.hpp"

namespace lidar_sgm {
namespace cuda {

class CudaMatcher final : public MatcherBackend {
 public:
  CudaMatcher();
  ~CudaMatcher() override;
  Backend backend() const override { return Backend::Cuda; }
  void run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
           FrameResults& out) override;
  /// The confidence's core part runs on the device too (confidence.cu).
  bool computesConfidence() const override { return true; }
  /// The LiDAR-gated search: windows from the host, Eq. 1 and the selection on them (aggregation.cu).
  bool searchesGatedWindows() const override { return true; }

  // Frames in device memory (device_frame.cpp, and runStages with the inputs on the device).
  bool readsDeviceMemory() const override { return true; }
  void copyToHost(const DeviceFrame& frame, bool images, DeviceFrameCopy& host) override;
  void copyToDevice(ImageView<const std::int16_t> host, ImageView<std::int16_t> device) override;
  void runOnDevice(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                   MemorySpace disparitySpace, FrameResults& out) override;

 private:
  struct Device;       // device buffers, stream and events (no CUDA type in this header)
  struct FrameImages;  // one frame's device images and volumes, as the stages hand them on
  void runStages(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity, FrameResults& out,
                 bool inputsOnDevice, bool outputOnDevice);
  void reserveImages(const FramePlan& plan, FrameImages& frame);
  void uploadCameras(const FramePlan& plan, const FrameInputs& in, bool inputsOnDevice, FrameImages& frame);
  void uploadLidar(const FramePlan& plan, const LidarPoints& lidar, FrameImages& frame);
  void searchWindows(const FramePlan& plan, FrameImages& frame);
  void censusTransforms(const FramePlan& plan, FrameImages& frame);
  void aggregatePaths(const FramePlan& plan, FrameImages& frame);
  void selectDisparity(const FramePlan& plan, FrameImages& frame);
  void leftRightCheck(const FramePlan& plan, FrameImages& frame);
  void confidence(const FramePlan& plan, FrameImages& frame);
  void downloadResults(const FramePlan& plan, bool outputOnDevice);
  void unpackResults(const FramePlan& plan, ImageView<std::int16_t> disparity, bool outputOnDevice,
                     FrameResults& out);
  void recordTimings(const FramePlan& plan, StageTimings& timings) const;

  std::unique_ptr<Device> device_;
};

/// "" when a CUDA device can run this build's kernels, else why not (no device, no driver ...).
std::string cudaUnavailableReason();

}  // namespace cuda
}  // namespace lidar_sgm
