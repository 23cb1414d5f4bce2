#include "lidar_sgm/core/matcher.hpp"

#include <chrono>
#include <cmath>
#include <utility>
#include <sstream>
#include <stdexcept>

#include "core/backend_registry.hpp"
#include "core/fixed_point.hpp"
#include "core/confidence_inputs.hpp"
#include "core/half_scale.hpp"

namespace lidar_sgm {
namespace {

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The right image must match the left one in size and bit depth.
void checkSamePair(const GrayImageView& left, const GrayImageView& right) {
  if (right.width() != left.width() || right.height() != left.height()) {
    throw std::invalid_argument("left and right images differ in size: left " + sizeText(left.width(), left.height()) +
                                ", right " + sizeText(right.width(), right.height()));
  }
  if (left.gray8.empty() != right.gray8.empty()) {
    throw std::invalid_argument("left and right images differ in bit depth (one is 8-bit, the other 16-bit)");
  }
}

void checkOutput(ImageView<std::int16_t> disparity, int width, int height) {
  if (disparity.data == nullptr || disparity.width != width || disparity.height != height ||
      disparity.stride < width) {
    throw std::invalid_argument("the output disparity image is " + sizeText(disparity.width, disparity.height) +
                                " but the frame is " + sizeText(width, height));
  }
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

namespace {

// "" when `entry` can run on this machine.
std::string entryUnavailable(const detail::BackendEntry& entry) {
  return entry.unavailable == nullptr ? std::string() : entry.unavailable();
}

}  // namespace

std::string unavailableReason(Backend backend) {
  if (backend == Backend::Auto) return "";
  for (const detail::BackendEntry& entry : detail::builtinBackends()) {
    if (entry.backend == backend) return entryUnavailable(entry);
  }
  return "not built into this library" +
         std::string(backend == Backend::Cuda ? " (configure with the CUDA toolkit, LIDAR_SGM_WITH_CUDA=ON)"
                     : backend == Backend::Cpu ? " (configure with Highway, LIDAR_SGM_WITH_CPU_BACKEND=ON)"
                                               : "");
}

bool isAvailable(Backend backend) { return unavailableReason(backend).empty(); }

Backend resolve(Backend backend) {
  if (backend != Backend::Auto) return backend;
  for (const detail::BackendEntry& entry : detail::builtinBackends()) {
    if (entryUnavailable(entry).empty()) return entry.backend;
  }
  return Backend::CpuRef;  // always built, always runs
}

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
  const Backend wanted = resolve(backend);
  std::string available;
  for (const detail::BackendEntry& entry : detail::builtinBackends()) {
    if (entry.backend == wanted) {
      const std::string why = entryUnavailable(entry);
      if (!why.empty()) throw std::runtime_error("backend " + toString(wanted) + " cannot run here: " + why);
      return entry.create(params);
    }
    available += toString(entry.backend) + ", ";
  }
  throw std::runtime_error("backend " + toString(backend) + " is not built into this library; available: " +
                           available + "auto");
}

Matcher::Matcher(const Parameters& params)
    : params_(params), scratch_(std::make_shared<ConfidenceScratch>()) {
  validate(params_);
}

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
    checkSamePair(left, right);
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
  checkOutput(disparity, width, height);
  timings_ = StageTimings{};
  rescaleMs_ = 0;
  if (!params_.confidence) confidence_ = Image<std::uint8_t>();
  if (params_.scale == 1.0f) {
    dispatch(left, right, vertical, lidar, mode, disparity);
  } else {
    computeAtHalfScale(left, right, vertical, lidar, mode, disparity);
  }
  lastMode_ = mode;
  lastUpCamera_ = haveUp;
}

void Matcher::computeOnDevice(const DeviceFrame& frame, ImageView<std::int16_t> disparity,
                              MemorySpace disparitySpace) {
  const bool haveLidar = frame.lidar != nullptr && frame.lidarCount > 0;
  const bool haveRight = !frame.right.empty();
  if (!haveRight && !haveLidar) {
    throw std::invalid_argument(
        "no input to match: give a right image (stereo), LiDAR points (LiDAR-only), or both (fused)");
  }
  const MatchMode mode = haveRight ? (haveLidar ? MatchMode::Fused : MatchMode::StereoOnly) : MatchMode::LidarOnly;
  const int width = frame.left.empty() ? frame.width : frame.left.width();
  const int height = frame.left.empty() ? frame.height : frame.left.height();
  if (haveRight && frame.left.empty()) throw std::invalid_argument("the left image is empty");
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("DeviceFrame without a left image must give its size (width, height), got " +
                                sizeText(width, height));
  }
  if (haveRight) checkSamePair(frame.left, frame.right);
  checkOutput(disparity, width, height);
  timings_ = StageTimings{};
  rescaleMs_ = 0;
  if (!params_.confidence) confidence_ = Image<std::uint8_t>();
  runOnDevice(frame, mode, disparity, disparitySpace);
  recordFrame(mode, false);
}

void Matcher::runOnDevice(const DeviceFrame&, MatchMode, ImageView<std::int16_t>, MemorySpace) {
  throw std::runtime_error("backend " + toString(backend()) +
                           " reads host memory only; computeOnDevice needs the cuda backend");
}

void Matcher::dispatch(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                       const LidarPoints* lidar, MatchMode mode, ImageView<std::int16_t> disparity) {
  Parameters matched = params_;
  if (params_.scale != 1.0f) {
    // The half-scale image sees every disparity halved: search half the range (Sec. IV-F).
    matched.numDisparities = params_.numDisparities / 2;
    matched.minDisparity = params_.minDisparity / 2;
    matched.disp12MaxDiff = params_.disp12MaxDiff / 2;
    matched.scale = 1.0f;
  }
  if (!vertical.up.empty()) {
    runWithUpCamera(matched, left, right, vertical.up, baselineRatio16(vertical.baselineRatio), lidar, mode,
                    disparity);
  } else {
    run(matched, left, right, lidar, mode, disparity);
  }
  if (params_.confidence && !computesConfidence()) computeConfidence(left, mode, disparity);
}

void Matcher::computeConfidence(const GrayImageView& left, MatchMode mode, ImageView<const std::int16_t> disparity) {
  const auto start = std::chrono::steady_clock::now();
  const int W = disparity.width;
  const int H = disparity.height;
  ConfidenceInputs& in = confidenceInputs_;
  if (mode == MatchMode::LidarOnly) {
    in.leftRightDifference.resize(W, H);
    in.leftRightDifference.fill(kNoCounterpartDifference);
  }
  in.lidarDistance.resize(W, H);
  lidarDistance(static_cast<const Image<std::uint8_t>&>(support_).view(), in.lidarDistance.view(), *scratch_);
  in.texture.resize(W, H);
  in.saturated.resize(W, H);
  textureAndSaturation(mode == MatchMode::LidarOnly ? GrayImageView() : left, in.texture.view(), in.saturated.view(),
                       *scratch_);
  confidence_.resize(W, H);
  in.disparityRange.resize(W, H);
  disparityRange(disparity, in.disparityRange.view(), *scratch_);
  combineConfidence(in, mode, params_.paths, disparity, confidence_.view());
  timings_.confidence = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// Scales a gray image of either depth down into the matching owned buffer.
GrayImageView downscaled(const GrayImageView& in, Image<std::uint8_t>& buffer8, Image<std::uint16_t>& buffer16) {
  if (in.empty()) return {};
  if (!in.gray8.empty()) {
    downscaleHalf(in.gray8, buffer8);
    return GrayImageView(static_cast<const Image<std::uint8_t>&>(buffer8).view());
  }
  downscaleHalf(in.gray16, buffer16);
  return GrayImageView(static_cast<const Image<std::uint16_t>&>(buffer16).view());
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void Matcher::computeAtHalfScale(const GrayImageView& left, const GrayImageView& right,
                                 const VerticalView& vertical, const LidarPoints* lidar, MatchMode mode,
                                 ImageView<std::int16_t> disparity) {
  auto start = std::chrono::steady_clock::now();
  const GrayImageView halfLeft = downscaled(left, half8_[0], half16_[0]);
  const GrayImageView halfRight = downscaled(right, half8_[1], half16_[1]);
  VerticalView halfVertical;
  if (!vertical.up.empty()) {
    halfVertical.up = downscaled(vertical.up, half8_[2], half16_[2]);
    halfVertical.baselineRatio = vertical.baselineRatio;
  }
  LidarPoints halfLidar;
  if (lidar != nullptr && !lidar->empty()) halfLidar = halveLidarPoints(*lidar);
  halfDisparity_.resize(halfSize(disparity.width), halfSize(disparity.height));
  rescaleMs_ = msSince(start);

  dispatch(halfLeft, halfRight, halfVertical, halfLidar.empty() ? nullptr : &halfLidar, mode,
           halfDisparity_.view());

  start = std::chrono::steady_clock::now();
  upscaleDisparity(static_cast<const Image<std::int16_t>&>(halfDisparity_).view(), disparity);
  std::swap(halfSupport_, support_);  // the backend wrote the half-scale support
  support_.resize(disparity.width, disparity.height);
  if (halfSupport_.empty()) {
    support_.fill(0);
  } else {
    upscaleMask(static_cast<const Image<std::uint8_t>&>(halfSupport_).view(), support_.view());
  }
  if (params_.confidence) {
    std::swap(halfConfidence_, confidence_);
    confidence_.resize(disparity.width, disparity.height);
    upscaleMask(static_cast<const Image<std::uint8_t>&>(halfConfidence_).view(), confidence_.view());
  }
  rescaleMs_ += msSince(start);
}

void Matcher::runWithUpCamera(const Parameters&, const GrayImageView&, const GrayImageView&, const GrayImageView&,
                              int, const LidarPoints*, MatchMode, ImageView<std::int16_t>) {
  throw std::runtime_error("backend " + toString(backend()) +
                           " has no Triple-SGM (third camera) stages; use cpu_ref");
}

}  // namespace lidar_sgm
