#include "lidar_sgm/eval/methods.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "baselines.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/min_confidence.hpp"

namespace lidar_sgm {
namespace eval {

const std::vector<MethodKind>& allMethodKinds() {
  static const std::vector<MethodKind> kinds{MethodKind::StereoSgm,     MethodKind::LidarSgm,   MethodKind::FusedSgm,
                                             MethodKind::OpenCvSgbm,    MethodKind::Morphological,
                                             MethodKind::ThreeCameras, MethodKind::ThreeCamerasLidar};
  return kinds;
}

const char* methodId(MethodKind kind) {
  switch (kind) {
    case MethodKind::StereoSgm: return "stereo_sgm";
    case MethodKind::LidarSgm: return "lidar_sgm";
    case MethodKind::FusedSgm: return "fused_sgm";
    case MethodKind::OpenCvSgbm: return "opencv_sgbm";
    case MethodKind::Morphological: return "ip_basic";
    case MethodKind::ThreeCameras: return "triple_sgm";
    case MethodKind::ThreeCamerasLidar: return "triple_fused_sgm";
  }
  return "?";
}

MethodKind methodKindFromId(const std::string& id) {
  std::string known;
  for (MethodKind kind : allMethodKinds()) {
    if (id == methodId(kind)) return kind;
    known += std::string(known.empty() ? "" : ", ") + methodId(kind);
  }
  throw std::invalid_argument("unknown method '" + id + "' (known: " + known + ")");
}

bool sameMethod(const Method& a, const Method& b) {
  // The sweep's alphas are rounded to 1e-3, so a tolerance well below that is exact enough.
  return a.kind == b.kind && (!a.usesAlpha() || std::abs(a.alpha - b.alpha) < 1e-9);
}

std::string displayName(const Method& method) {
  char alphaText[32];
  std::snprintf(alphaText, sizeof(alphaText), "%.2g", method.alpha);
  switch (method.kind) {
    case MethodKind::StereoSgm: return "stereo-only SGM";
    case MethodKind::LidarSgm: return "LiDAR-only SGM";
    case MethodKind::FusedSgm: return std::string("LiDAR-SGM (alpha ") + alphaText + ")";
    case MethodKind::OpenCvSgbm: return "OpenCV StereoSGBM";
    case MethodKind::Morphological: return "IP-Basic (morphological)";
    case MethodKind::ThreeCameras: return "3 cameras (Triple-SGM)";
    case MethodKind::ThreeCamerasLidar: return std::string("3 cameras + LiDAR (alpha ") + alphaText + ")";
  }
  return "?";
}

int numDisparitiesAt(int frameNumDisparities, float scale) {
  if (scale == 1.0f) return frameNumDisparities;
  return std::min(512, 32 * ((frameNumDisparities + 31) / 32));
}

namespace {

/// A LiDAR-SGM method as the tools run it: the Densifier on the frame's projected scan, its mode
/// following the inputs it is given (and the LiDAR-only crop on, its default).
void runDensifier(const Method& method, const EvalFrame& frame, const DensifierConfig& config, MethodOutput& out) {
  const bool images = method.kind != MethodKind::LidarSgm;
  const bool lidar = method.kind == MethodKind::LidarSgm || method.kind == MethodKind::FusedSgm ||
                     method.kind == MethodKind::ThreeCamerasLidar;
  // Every pixel first (the confidence curves need them), then the Densifier's own last step;
  // the protocols score the disparity, no cloud.
  DensifierConfig all = config;
  all.minConfidence = 0.0;
  all.computeCloud = false;
  Densifier densifier;
  densifier.setConfig(all);
  if (images) densifier.setStereoPair(io::grayView(frame.left), io::grayView(frame.right));
  if (method.needsThirdCamera()) densifier.setUpCamera(io::grayView(frame.up), frame.upBaselineRatio);
  densifier.runProjected(lidar ? &frame.lidar : nullptr);
  out.allDisparity = densifier.disparity();
  out.confidence = densifier.confidence();
  out.disparity = out.allDisparity;
  if (!out.confidence.empty()) {
    Image<std::uint8_t> kept = out.confidence;
    applyMinConfidence(out.disparity.view(), kept.view(), config.minConfidence);
  }
  if (densifier.matcher() != nullptr) out.confidenceInputs = densifier.matcher()->confidenceInputs();
  out.range = densifier.usedDisparityRange();
}

}  // namespace

MethodOutput runMethod(const Method& method, const EvalFrame& frame, const DensifierConfig& config,
                       int fixedNumDisparities) {
  if (method.needsThirdCamera() && frame.up.empty()) {
    throw std::invalid_argument(displayName(method) + " needs a third camera; frame " + frame.name + " has none");
  }
  MethodOutput out;
  const auto start = std::chrono::steady_clock::now();
  switch (method.kind) {
    case MethodKind::OpenCvSgbm:
      out.disparity = opencvSgbm(frame.left, frame.right, frame.numDisparities, 5);
      out.range.numDisparities = frame.numDisparities;
      break;
    case MethodKind::Morphological:
      out.disparity = morphologicalCompletion(frame.lidarSparse, frame.focalBaseline);
      break;
    case MethodKind::StereoSgm:
    case MethodKind::LidarSgm:
    case MethodKind::FusedSgm:
    case MethodKind::ThreeCameras:
    case MethodKind::ThreeCamerasLidar: {
      DensifierConfig c = config;
      c.matcher.numDisparities = numDisparitiesAt(fixedNumDisparities > 0 ? fixedNumDisparities : frame.numDisparities,
                                                  config.matcher.scale);
      // The kinds without a LiDAR weight of their own have it by definition (MethodKind).
      c.matcher.alpha = static_cast<float>(method.usesAlpha() ? method.alpha
                                           : method.kind == MethodKind::LidarSgm ? 1.0 : 0.0);
      runDensifier(method, frame, c, out);
      break;
    }
  }
  out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eval
}  // namespace lidar_sgm
