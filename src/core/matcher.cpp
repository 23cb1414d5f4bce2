#include "lidar_sgm/core/matcher.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "backends/cpu_ref/cpu_ref_matcher.hpp"
#include "lidar_sgm/core/stages.hpp"

namespace lidar_sgm {
namespace {

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

}  // namespace

std::string toString(Backend backend) {
  switch (backend) {
    case Backend::Auto: return "auto";
    case Backend::CpuRef: return "cpu_ref";
    case Backend::Cpu: return "cpu";
    case Backend::Cuda: return "cuda";
  }
  return "unknown";
}

Backend backendFromString(const std::string& name) {
  for (Backend b : {Backend::Auto, Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
    if (toString(b) == name) return b;
  }
  throw std::invalid_argument("unknown backend '" + name + "': must be auto, cpu_ref, cpu or cuda");
}

bool isAvailable(Backend backend) { return backend == Backend::Auto || backend == Backend::CpuRef; }

std::string toString(MatchMode mode) {
  switch (mode) {
    case MatchMode::StereoOnly: return "stereo-only";
    case MatchMode::LidarOnly: return "lidar-only";
    case MatchMode::Fused: return "fused";
  }
  return "unknown";
}

std::string toString(MatchMode mode, bool upCamera) {
  return upCamera && mode != MatchMode::LidarOnly ? toString(mode) + " (3 cameras)" : toString(mode);
}

std::unique_ptr<Matcher> Matcher::create(Backend backend, const Parameters& params) {
  validate(params);
  switch (backend) {
    case Backend::Auto:
    case Backend::CpuRef: return std::make_unique<CpuRefMatcher>(params);
    case Backend::Cpu:
    case Backend::Cuda: break;
  }
  throw std::runtime_error("backend " + toString(backend) +
                           " is not built into this library; available: cpu_ref (or auto)");
}

Matcher::Matcher(const Parameters& params) : params_(params) { validate(params_); }

void Matcher::setParameters(const Parameters& params) {
  validate(params);
  params_ = params;
}

void Matcher::compute(const GrayImageView& left, const GrayImageView& right, const LidarPoints* lidar,
                      ImageView<std::int16_t> disparity) {
  compute(left, right, VerticalView{}, lidar, disparity);
}

void Matcher::compute(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                      const LidarPoints* lidar, ImageView<std::int16_t> disparity) {
  const bool haveLidar = lidar != nullptr && !lidar->empty();
  const bool haveRight = !right.empty();
  const bool haveUp = !vertical.up.empty();
  if (!haveUp && vertical.baselineRatio != 0.0) {
    std::ostringstream os;
    os << "VerticalView has baselineRatio " << vertical.baselineRatio
       << " but no up image: pass the up image, or an empty VerticalView (ratio 0) for two cameras";
    throw std::invalid_argument(os.str());
  }
  if (haveUp && !haveRight) {
    throw std::invalid_argument(
        "an up image (third camera) needs a right image too: Triple-SGM adds the vertical pair to the "
        "horizontal one; there is no up-only mode");
  }
  if (haveUp && (!std::isfinite(vertical.baselineRatio) || vertical.baselineRatio <= 0.0 ||
                 vertical.baselineRatio > 4.0)) {
    std::ostringstream os;
    os << "invalid VerticalView baselineRatio = " << vertical.baselineRatio
       << ": must be b_up / b, finite, in (0, 4]";
    throw std::invalid_argument(os.str());
  }
  MatchMode mode;
  if (haveRight) {
    mode = haveLidar ? MatchMode::Fused : MatchMode::StereoOnly;
  } else if (haveLidar) {
    mode = MatchMode::LidarOnly;
  } else {
    throw std::invalid_argument(
        "no input to match: give a right image (stereo), LiDAR points (LiDAR-only), or both (fused)");
  }
  int width = 0;
  int height = 0;
  if (mode == MatchMode::LidarOnly) {
    width = lidar->width();
    height = lidar->height();
    if (!left.empty() && (left.width() != width || left.height() != height)) {
      throw std::invalid_argument("LiDAR points are for a " + sizeText(width, height) +
                                  " image but the left image is " + sizeText(left.width(), left.height()));
    }
  } else {
    if (left.empty()) throw std::invalid_argument("the left image is empty");
    width = left.width();
    height = left.height();
    if (right.width() != width || right.height() != height) {
      throw std::invalid_argument("left and right images differ in size: left " + sizeText(width, height) +
                                  ", right " + sizeText(right.width(), right.height()));
    }
    if (left.gray8.empty() != right.gray8.empty()) {
      throw std::invalid_argument("left and right images differ in bit depth (one is 8-bit, the other 16-bit)");
    }
    if (haveLidar && (lidar->width() != width || lidar->height() != height)) {
      throw std::invalid_argument("LiDAR points are for a " + sizeText(lidar->width(), lidar->height()) +
                                  " image but the stereo images are " + sizeText(width, height));
    }
    if (haveUp && (vertical.up.width() != width || vertical.up.height() != height)) {
      throw std::invalid_argument("left and up images differ in size: left " + sizeText(width, height) +
                                  ", up " + sizeText(vertical.up.width(), vertical.up.height()));
    }
    if (haveUp && left.gray8.empty() != vertical.up.gray8.empty()) {
      throw std::invalid_argument("left and up images differ in bit depth (one is 8-bit, the other 16-bit)");
    }
  }
  if (disparity.empty() || disparity.width != width || disparity.height != height ||
      disparity.stride < width) {
    throw std::invalid_argument("the output disparity image is " + sizeText(disparity.width, disparity.height) +
                                " but the frame is " + sizeText(width, height));
  }
  timings_ = StageTimings{};
  if (haveUp) {
    runWithUpCamera(left, right, vertical.up, baselineRatio16(vertical.baselineRatio), lidar, mode, disparity);
  } else {
    run(left, right, lidar, mode, disparity);
  }
  lastMode_ = mode;
  lastUpCamera_ = haveUp;
}

void Matcher::runWithUpCamera(const GrayImageView&, const GrayImageView&, const GrayImageView&, int,
                              const LidarPoints*, MatchMode, ImageView<std::int16_t>) {
  throw std::runtime_error("backend " + toString(backend()) +
                           " has no Triple-SGM (third camera) stages; use cpu_ref");
}

}  // namespace lidar_sgm
