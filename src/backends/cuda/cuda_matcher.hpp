#pragma once
// The CUDA backend's matcher: uploads a frame, runs the stages of kernels.hpp on one stream and
// downloads the disparity and what the core needs besides it (support, confidence inputs).

#include <cstdint>
#include <memory>

#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace cuda {

class CudaMatcher final : public Matcher {
 public:
  explicit CudaMatcher(const Parameters& params);
  ~CudaMatcher() override;
  Backend backend() const override { return Backend::Cuda; }

 protected:
  /// The confidence's core part runs on the device too (confidence.cu).
  bool computesConfidence() const override { return true; }
  void run(const Parameters& params, const GrayImageView& left, const GrayImageView& right, const LidarPoints* lidar,
           MatchMode mode, ImageView<std::int16_t> disparity) override;
  void runWithUpCamera(const Parameters& params, const GrayImageView& left, const GrayImageView& right,
                       const GrayImageView& up, int ratio16, const LidarPoints* lidar, MatchMode mode,
                       ImageView<std::int16_t> disparity) override;
  void runOnDevice(const DeviceFrame& frame, MatchMode mode, ImageView<std::int16_t> disparity,
                   MemorySpace disparitySpace) override;

 private:
  struct Device;  // device buffers, stream and events (no CUDA type in this header)
  void runStages(const Parameters& params, const GrayImageView& left, const GrayImageView& right,
                 const GrayImageView* up, int ratio16, const LidarPoints* lidar, MatchMode mode,
                 ImageView<std::int16_t> disparity, bool inputsOnDevice = false, bool outputOnDevice = false);
  struct HostCopies;
  std::unique_ptr<Device> device_;
  std::unique_ptr<HostCopies> hostCopies_;
};

/// "" when a CUDA device can run this build's kernels, else why not (no device, no driver ...).
std::string cudaUnavailableReason();

}  // namespace cuda
}  // namespace lidar_sgm
