#pragma once
// What the Matcher facade keeps between frames: its backend, the results the backend writes,
// and the core's own buffers (half-scale inputs, the confidence's row buffers, host copies of
// device frames). The facade validates and plans a frame; Impl runs the plan.

#include <cstdint>
#include <memory>

#include "core/backend.hpp"
#include "core/confidence_inputs.hpp"
#include "core/frame_plan.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

struct Matcher::Impl {
  Parameters params;
  std::unique_ptr<MatcherBackend> backend;
  FrameResults results;
  MatchMode lastMode = MatchMode::StereoOnly;
  bool lastUpCamera = false;
  double rescaleMs = 0;
  DeviceFrameCopy deviceCopy;  ///< computeOnDevice's host copies

  /// Clears what the last frame left that this one may not overwrite.
  void beginFrame();
  /// Runs `plan` on the full-scale inputs: directly, or at half scale between the core's
  /// resampling of the inputs and of the results.
  void run(const FramePlan& plan, const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
           const LidarPoints* lidar, ImageView<std::int16_t> disparity);

 private:
  /// The backend, then the confidence's core part, on inputs at the plan's size.
  void runBackend(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity);
  void runAtHalfScale(const FramePlan& plan, const GrayImageView& left, const GrayImageView& right,
                      const VerticalView& vertical, const LidarPoints* lidar, ImageView<std::int16_t> disparity);
  void computeConfidence(const FramePlan& plan, const GrayImageView& left, ImageView<const std::int16_t> disparity);

  ConfidenceScratch confidenceScratch;
  // Half-scale buffers: the inputs (left, right, up) of either depth, the backend's outputs.
  Image<std::uint8_t> half8[3];
  Image<std::uint16_t> half16[3];
  Image<std::int16_t> halfDisparity;
  Image<std::uint8_t> halfSupport;
  Image<std::uint8_t> halfConfidence;
  std::vector<LidarSample> halfSamples;  // the halved points, kept between frames
  LidarPoints halfLidar;
};

}  // namespace lidar_sgm
