#include "core/frame_plan.hpp"

#include "core/fixed_point.hpp"
#include "core/half_scale.hpp"

namespace lidar_sgm {

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

FramePlan planFrame(const Parameters& params, MatchMode mode, int width, int height, double upBaselineRatio) {
  FramePlan plan;
  plan.mode = mode;
  plan.halfScale = params.scale != 1.0f;
  plan.width = plan.halfScale ? halfSize(width) : width;
  plan.height = plan.halfScale ? halfSize(height) : height;
  plan.params = params;
  if (plan.halfScale) {
    // The half-scale image sees every disparity halved: search half the range (Sec. IV-F).
    plan.params.numDisparities = params.numDisparities / 2;
    plan.params.minDisparity = params.minDisparity / 2;
    plan.params.disp12MaxDiff = params.disp12MaxDiff / 2;
    plan.params.scale = 1.0f;
  }
  plan.minDisparity = plan.params.minDisparity;
  plan.D = plan.params.numDisparities;

  const bool up = upBaselineRatio != 0.0 && mode != MatchMode::LidarOnly;
  plan.cameras = mode == MatchMode::LidarOnly ? 0 : up ? 3 : 2;
  plan.ratio16 = up ? baselineRatio16(upBaselineRatio) : 0;
  plan.censusScale = params.censusType == CensusType::Census9x7 ? 1 : 2;

  plan.useLidar = mode != MatchMode::StereoOnly;
  plan.alphaWeight = alphaWeight(params.alpha);
  plan.adaptiveAlpha = mode == MatchMode::Fused && params.alphaMode == AlphaMode::Adaptive;

  // The check in fused mode is opt-in (Parameters::lrCheckWithLidar); LiDAR-only has no right view.
  plan.lrCheck = mode == MatchMode::StereoOnly ? params.lrCheck
                                               : mode == MatchMode::Fused && params.lrCheck && params.lrCheckWithLidar;
  plan.lrCheckTrustsLidar = mode == MatchMode::Fused;
  plan.gatedSearch = params.gatedSearch && mode == MatchMode::Fused;
  plan.confidence = params.confidence;
  plan.confidenceLr = params.confidence && mode != MatchMode::LidarOnly;
  return plan;
}

}  // namespace lidar_sgm
