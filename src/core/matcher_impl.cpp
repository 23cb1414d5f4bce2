// Running a planned frame: the backend, the core's half-scale resampling around it, and the
// confidence's core part.
#include "core/matcher_impl.hpp"

#include <chrono>
#include <utility>

#include "core/half_scale.hpp"

namespace lidar_sgm {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Only what the plan uses reaches the backend.
FrameInputs planned(const FramePlan& plan, const GrayImageView& left, const GrayImageView& right,
                    const GrayImageView& up, const LidarPoints* lidar) {
  FrameInputs in;
  if (plan.useCameras()) {
    in.left = left;
    in.right = right;
  }
  if (plan.upCamera()) in.up = up;
  if (plan.useLidar) in.lidar = lidar;
  return in;
}

}  // namespace

void Matcher::Impl::beginFrame() {
  results.timings = StageTimings{};
  rescaleMs = 0;
  if (!params.confidence) results.confidence = Image<std::uint8_t>();
}

void Matcher::Impl::run(const FramePlan& plan, const GrayImageView& left, const GrayImageView& right,
                        const VerticalView& vertical, const LidarPoints* lidar, ImageView<std::int16_t> disparity) {
  if (plan.halfScale) {
    runAtHalfScale(plan, left, right, vertical, lidar, disparity);
  } else {
    runBackend(plan, planned(plan, left, right, vertical.up, lidar), disparity);
  }
}

void Matcher::Impl::runBackend(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity) {
  backend->run(plan, in, disparity, results);
  if (plan.confidence && !backend->computesConfidence()) computeConfidence(plan, in.left, disparity);
}

void Matcher::Impl::runAtHalfScale(const FramePlan& plan, const GrayImageView& left, const GrayImageView& right,
                                   const VerticalView& vertical, const LidarPoints* lidar,
                                   ImageView<std::int16_t> disparity) {
  auto start = std::chrono::steady_clock::now();
  // The resampling on the backend's threads (rows split; no result depends on their count).
  const int threads = effectiveThreads(params);
  const GrayImageView halfLeft = downscaleHalf(left, half8[0], half16[0], threads);
  const GrayImageView halfRight = downscaleHalf(right, half8[1], half16[1], threads);
  const GrayImageView halfUp = downscaleHalf(vertical.up, half8[2], half16[2], threads);
  const bool halfWithLidar = lidar != nullptr && !lidar->empty();
  if (halfWithLidar) halveLidarPoints(*lidar, halfSamples, halfLidar);
  halfDisparity.resize(plan.width, plan.height);
  rescaleMs = msSince(start);

  runBackend(plan, planned(plan, halfLeft, halfRight, halfUp, halfWithLidar ? &halfLidar : nullptr),
             halfDisparity.view());

  start = std::chrono::steady_clock::now();
  upscaleDisparity(std::as_const(halfDisparity).view(), disparity, threads);
  std::swap(halfSupport, results.support);  // the backend wrote the half-scale support
  results.support.resize(disparity.width, disparity.height);
  if (halfSupport.empty()) {
    results.support.fill(0);
  } else {
    upscaleMask(std::as_const(halfSupport).view(), results.support.view(), threads);
  }
  if (plan.confidence) {
    std::swap(halfConfidence, results.confidence);
    results.confidence.resize(disparity.width, disparity.height);
    upscaleMask(std::as_const(halfConfidence).view(), results.confidence.view(), threads);
  }
  rescaleMs += msSince(start);
}

void Matcher::Impl::computeConfidence(const FramePlan& plan, const GrayImageView& left,
                                      ImageView<const std::int16_t> disparity) {
  const auto start = std::chrono::steady_clock::now();
  const int W = disparity.width;
  const int H = disparity.height;
  ConfidenceInputs& in = results.confidenceInputs;
  if (plan.mode == MatchMode::LidarOnly) {
    in.leftRightDifference.resize(W, H);
    in.leftRightDifference.fill(kNoCounterpartDifference);
  }
  in.lidarDistance.resize(W, H);
  lidarDistance(std::as_const(results.support).view(), in.lidarDistance.view(), confidenceScratch);
  in.texture.resize(W, H);
  in.saturated.resize(W, H);
  textureAndSaturation(left, in.texture.view(), in.saturated.view(), confidenceScratch);
  results.confidence.resize(W, H);
  in.disparityRange.resize(W, H);
  disparityRange(disparity, in.disparityRange.view(), confidenceScratch);
  combineConfidence(in, plan.mode, plan.params.paths, disparity, results.confidence.view());
  results.timings.confidence = msSince(start);
}

}  // namespace lidar_sgm
