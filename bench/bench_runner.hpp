#pragma once
// What the bench times per frame: the Densifier every tool runs (projected scan in, disparity
// out, no cloud), or, where lidar_sgm::pipeline is not built (a machine without Eigen, e.g. the
// GPU machine), the core's Matcher it delegates to.

#include <memory>

#include "bench_frame.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace bench {

class FrameRunner {
 public:
  /// The inputs of `mode`: stereo-only gets no LiDAR, LiDAR-only no images. Throws
  /// std::logic_error when the backend made is not `backend` resolved.
  FrameRunner(Backend backend, const Parameters& params, const Frame& frame, MatchMode mode);
  ~FrameRunner();
  FrameRunner(const FrameRunner&) = delete;
  FrameRunner& operator=(const FrameRunner&) = delete;

  /// One frame, as a caller of the library waits for it.
  void run();
  MatchMode lastMode() const;
  const StageTimings& stages() const;
  double rescaleMs() const;
  /// "Densifier" or "Matcher": what run() times, for the settings block.
  static const char* timedApi();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bench
}  // namespace lidar_sgm
