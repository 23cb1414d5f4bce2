// The Matcher facade: checks a frame, plans it once (frame_plan.hpp) and hands the plan to the
// backend behind it (matcher_impl.cpp runs it).
#include "lidar_sgm/core/matcher.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/backend_registry.hpp"
#include "core/frame_checks.hpp"
#include "core/frame_plan.hpp"
#include "core/matcher_impl.hpp"

namespace lidar_sgm {
namespace {

// A host disparity image into the caller's, in either memory space.
void copyDisparity(MatcherBackend& backend, ImageView<const std::int16_t> host, ImageView<std::int16_t> disparity,
                   MemorySpace disparitySpace) {
  if (disparitySpace == MemorySpace::Device) {
    backend.copyToDevice(host, disparity);
    return;
  }
  for (int y = 0; y < host.height; ++y) std::copy(host.row(y), host.row(y) + host.width, disparity.row(y));
}

// No silent fallback to the full search: a backend without the gated search refuses the option.
void checkBackendSupports(const MatcherBackend& backend, const Parameters& params) {
  if (params.gatedSearch && !backend.searchesGatedWindows()) {
    throw std::invalid_argument("invalid parameter gatedSearch (on by default; -no_gated_search turns it off): backend " + toString(backend.backend()) +
                                " does not implement the gated search; use backend cpu or cpu_ref");
  }
}

}  // namespace

std::unique_ptr<Matcher> Matcher::create(Backend backend, const Parameters& params) {
  validate(params);
  auto impl = std::make_unique<Impl>();
  impl->params = params;
  impl->backend = detail::createBackend(backend);
  checkBackendSupports(*impl->backend, params);
  return std::unique_ptr<Matcher>(new Matcher(std::move(impl)));
}

Matcher::Matcher(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Matcher::~Matcher() = default;

Backend Matcher::backend() const { return impl_->backend->backend(); }

const Parameters& Matcher::parameters() const { return impl_->params; }

void Matcher::setParameters(const Parameters& params) {
  validate(params);
  checkBackendSupports(*impl_->backend, params);
  impl_->params = params;
}

void Matcher::compute(const GrayImageView& left, const GrayImageView& right, const LidarPoints* lidar,
                      ImageView<std::int16_t> disparity) {
  compute(left, right, VerticalView{}, lidar, disparity);
}

void Matcher::compute(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                      const LidarPoints* lidar, ImageView<std::int16_t> disparity) {
  const CheckedFrame frame = checkFrame(left, right, vertical, lidar, disparity);
  Impl& m = *impl_;
  const FramePlan plan = planFrame(m.params, frame.mode, frame.width, frame.height, vertical.baselineRatio);
  m.beginFrame();
  m.run(plan, left, right, vertical, lidar, disparity);
  m.lastMode = frame.mode;
  m.lastUpCamera = plan.upCamera();
}

void Matcher::computeOnDevice(const DeviceFrame& frame, ImageView<std::int16_t> disparity,
                              MemorySpace disparitySpace) {
  const CheckedFrame checked = checkDeviceFrame(frame, disparity);
  Impl& m = *impl_;
  if (!m.backend->readsDeviceMemory()) {
    throw std::runtime_error("backend " + toString(backend()) +
                             " reads host memory only; computeOnDevice needs the cuda backend");
  }
  const FramePlan plan = planFrame(m.params, checked.mode, checked.width, checked.height, 0.0);
  m.beginFrame();
  // The LiDAR samples come back to be validated and bucketed by LidarPoints, which names a
  // sample outside the image or behind the camera (12 bytes a point).
  // At half scale the images come back too: LiDAR-only mode matches none.
  DeviceFrameCopy& host = m.deviceCopy;
  host.left = GrayImageView();
  host.right = GrayImageView();
  m.backend->copyToHost(frame, /*images=*/plan.halfScale && plan.useCameras(), host);
  LidarPoints points;
  if (plan.useLidar) points = LidarPoints(checked.width, checked.height, host.samples);
  const LidarPoints* lidar = plan.useLidar ? &points : nullptr;
  if (plan.halfScale) {
    // The half-scale resampling is the core's, on the host: match the host copies.
    host.disparity.resize(checked.width, checked.height);
    compute(host.left, host.right, lidar, host.disparity.view());
    copyDisparity(*m.backend, std::as_const(host.disparity).view(), disparity, disparitySpace);
  } else {
    // The confidence, too, is computed on the device (the backend computesConfidence()).
    FrameInputs in;
    if (plan.useCameras()) {
      in.left = frame.left;
      in.right = frame.right;
    }
    in.lidar = lidar;
    m.backend->runOnDevice(plan, in, disparity, disparitySpace, m.results);
  }
  m.lastMode = checked.mode;
  m.lastUpCamera = false;
}

MatchMode Matcher::lastMode() const { return impl_->lastMode; }
bool Matcher::lastUsedUpCamera() const { return impl_->lastUpCamera; }
const StageTimings& Matcher::lastTimings() const { return impl_->results.timings; }
ImageView<const std::uint8_t> Matcher::lidarSupport() const { return std::as_const(impl_->results.support).view(); }
ImageView<const std::uint8_t> Matcher::confidence() const { return std::as_const(impl_->results.confidence).view(); }
const ConfidenceInputs& Matcher::confidenceInputs() const { return impl_->results.confidenceInputs; }
double Matcher::lastRescaleMs() const { return impl_->rescaleMs; }

}  // namespace lidar_sgm
