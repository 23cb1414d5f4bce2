#pragma once
// The interface every backend implements, private to the core and the backends: Matcher (the
// public facade) validates a frame, plans it (frame_plan.hpp), rescales it at half scale and
// computes the confidence's core part; a backend only runs the stages of the plan it is handed.
// Each backend keeps its own buffers between frames; what the facade reads back lives in
// FrameResults, which the facade owns.

#include <cstdint>
#include <vector>

#include "core/frame_plan.hpp"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

/// A frame's inputs at the plan's size, validated. Only what the plan uses is set: `left` and
/// `right` are empty in LiDAR-only mode, `up` without the third camera, `lidar` null in
/// stereo-only mode.
struct FrameInputs {
  GrayImageView left;
  GrayImageView right;
  GrayImageView up;
  const LidarPoints* lidar = nullptr;
};

/// What a backend writes besides the disparity, at the plan's size.
struct FrameResults {
  StageTimings timings;
  Image<std::uint8_t> support;  ///< 1 where a LiDAR point touches the pixel's 3x3 neighbourhood (all 0 without LiDAR)
  /// The backend fills margin and bestCost when plan.confidence is set, and leftRightDifference
  /// when plan.confidenceLr is; the core the rest, unless the backend computesConfidence().
  ConfidenceInputs confidenceInputs;
  Image<std::uint8_t> confidence;  ///< written by a backend that computesConfidence()
};

/// Host copies of a frame given in device memory (Matcher::computeOnDevice), kept between frames.
struct DeviceFrameCopy {
  std::vector<LidarSample> samples;
  Image<std::uint8_t> left8, right8;
  Image<std::uint16_t> left16, right16;
  GrayImageView left, right;  ///< views of the buffers above, after copyToHost with images
  Image<std::int16_t> disparity;
};

class MatcherBackend {
 public:
  virtual ~MatcherBackend() = default;
  MatcherBackend() = default;
  MatcherBackend(const MatcherBackend&) = delete;
  MatcherBackend& operator=(const MatcherBackend&) = delete;

  virtual Backend backend() const = 0;

  /// Runs every stage of `plan` on `in` (host memory) into `disparity` (plan.width x
  /// plan.height). Writes out.support and the timings of its stages.
  virtual void run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                   FrameResults& out) = 0;

  /// Whether run() computes the whole confidence itself (out.confidence and every input), so
  /// that the core does not: a backend that keeps the frame in its own memory or threads.
  virtual bool computesConfidence() const { return false; }

  /// Whether the backend implements the LiDAR-gated search (Parameters::gatedSearch); if not,
  /// the facade refuses the option for it.
  virtual bool searchesGatedWindows() const { return false; }

  /// Whether the backend takes frames in device memory (the functions below); if not, the
  /// facade refuses computeOnDevice and never calls them.
  virtual bool readsDeviceMemory() const { return false; }
  /// The first call for a device frame: orders the backend's work after the work queued so far on
  /// frame.stream (the inputs' writer), then copies the device frame's LiDAR samples (if any)
  /// into host.samples and, with `images`, its left and right images into host.left / host.right.
  virtual void copyToHost(const DeviceFrame& frame, bool images, DeviceFrameCopy& host);
  /// Copies a host disparity image into device memory of the same size.
  virtual void copyToDevice(ImageView<const std::int16_t> host, ImageView<std::int16_t> device);
  /// run() on a full-scale frame whose images are in device memory (`in.lidar`: the samples,
  /// validated on the host); the disparity goes to `disparitySpace`.
  virtual void runOnDevice(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                           MemorySpace disparitySpace, FrameResults& out);
};

}  // namespace lidar_sgm
