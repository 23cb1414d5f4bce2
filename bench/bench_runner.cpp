#include "bench_runner.hpp"

#include <stdexcept>
#include <string>

#ifdef LIDAR_SGM_BENCH_HAVE_PIPELINE
#include "lidar_sgm/pipeline/densifier.hpp"
#endif

namespace lidar_sgm {
namespace bench {

namespace {

void checkBackend(Backend requested, Backend made) {
  if (made != resolve(requested)) {
    throw std::logic_error("asked for backend " + toString(resolve(requested)) + ", got " + toString(made));
  }
}

}  // namespace

#ifdef LIDAR_SGM_BENCH_HAVE_PIPELINE

struct FrameRunner::Impl {
  Densifier densifier;
  const LidarPoints* lidar = nullptr;
};

FrameRunner::FrameRunner(Backend backend, const Parameters& params, const Frame& frame, MatchMode mode)
    : impl_(new Impl) {
  Densifier& d = impl_->densifier;
  d.setBackend(backend);
  d.setParameters(params);
  // The paper's fixed range, not the frame's LiDAR's: the bench times a given search range and
  // compares with OpenCV SGBM at the same one.
  d.setDisparityRangeMode(DisparityRangeMode::Fixed);
  d.setComputeCloud(false);
  if (mode != MatchMode::LidarOnly) d.setStereoPair(frame.left.view(), frame.right.view());
  impl_->lidar = mode == MatchMode::StereoOnly ? nullptr : &frame.lidar;
  run();  // creates the matcher, so that its backend can be checked before any timing
  checkBackend(backend, d.usedBackend());
}

void FrameRunner::run() { impl_->densifier.runProjected(impl_->lidar); }
MatchMode FrameRunner::lastMode() const { return impl_->densifier.lastMode(); }
const StageTimings& FrameRunner::stages() const { return impl_->densifier.matcher()->lastTimings(); }
double FrameRunner::rescaleMs() const { return impl_->densifier.matcher()->lastRescaleMs(); }
const char* FrameRunner::timedApi() { return "Densifier::runProjected (the tools' pipeline, no cloud)"; }

#else

struct FrameRunner::Impl {
  std::unique_ptr<Matcher> matcher;
  GrayImageView left;
  GrayImageView right;
  const LidarPoints* lidar = nullptr;
  Image<std::int16_t> disparity;
};

FrameRunner::FrameRunner(Backend backend, const Parameters& params, const Frame& frame, MatchMode mode)
    : impl_(new Impl) {
  impl_->matcher = Matcher::create(backend, params);
  checkBackend(backend, impl_->matcher->backend());
  impl_->left = GrayImageView(frame.left.view());
  if (mode != MatchMode::LidarOnly) impl_->right = GrayImageView(frame.right.view());
  impl_->lidar = mode == MatchMode::StereoOnly ? nullptr : &frame.lidar;
  impl_->disparity = Image<std::int16_t>(frame.width(), frame.height());
}

void FrameRunner::run() { impl_->matcher->compute(impl_->left, impl_->right, impl_->lidar, impl_->disparity.view()); }
MatchMode FrameRunner::lastMode() const { return impl_->matcher->lastMode(); }
const StageTimings& FrameRunner::stages() const { return impl_->matcher->lastTimings(); }
double FrameRunner::rescaleMs() const { return impl_->matcher->lastRescaleMs(); }
const char* FrameRunner::timedApi() { return "Matcher::compute (lidar_sgm::pipeline not built)"; }

#endif

FrameRunner::~FrameRunner() = default;

}  // namespace bench
}  // namespace lidar_sgm
