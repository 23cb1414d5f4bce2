#include "eval/methods.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "eval/baselines.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace evaluation {

std::string Method::name() const {
  char alphaText[32];
  std::snprintf(alphaText, sizeof(alphaText), "%.2g", alpha);
  switch (kind) {
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

MethodOutput runMethod(const Method& method, const EvalFrame& frame, const Parameters& base, Backend backend) {
  Parameters params = base;
  params.numDisparities = numDisparitiesAt(frame.numDisparities, base.scale);
  params.alpha = static_cast<float>(method.alpha);
  MethodOutput out;
  out.disparity = Image<std::int16_t>(frame.left.cols, frame.left.rows, kInvalidDisparity);
  const auto start = std::chrono::steady_clock::now();
  if (method.needsThirdCamera() && frame.up.empty()) {
    throw std::invalid_argument(method.name() + " needs a third camera; frame " + frame.name + " has none");
  }
  switch (method.kind) {
    case MethodKind::OpenCvSgbm:
      out.disparity = opencvSgbm(frame.left, frame.right, frame.numDisparities, 5);
      break;
    case MethodKind::Morphological:
      out.disparity = morphologicalCompletion(frame.lidarSparse, frame.focalBaseline);
      break;
    default: {
      auto matcher = Matcher::create(backend, params);
      const GrayImageView left = io::grayView(frame.left);
      const GrayImageView right = io::grayView(frame.right);
      const LidarPoints* lidar = &frame.lidar;
      switch (method.kind) {
        case MethodKind::StereoSgm:
          matcher->compute(left, right, nullptr, out.disparity.view());
          break;
        case MethodKind::LidarSgm:
          matcher->compute(GrayImageView(), GrayImageView(), lidar, out.disparity.view());
          break;
        case MethodKind::FusedSgm:
          matcher->compute(left, right, lidar, out.disparity.view());
          break;
        case MethodKind::ThreeCameras:
        case MethodKind::ThreeCamerasLidar: {
          VerticalView up;
          up.up = io::grayView(frame.up);
          up.baselineRatio = frame.upBaselineRatio;
          matcher->compute(left, right, up, method.kind == MethodKind::ThreeCamerasLidar ? lidar : nullptr,
                           out.disparity.view());
          break;
        }
        default:
          break;
      }
    }
  }
  out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace evaluation
}  // namespace lidar_sgm
