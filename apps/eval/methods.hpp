#pragma once
// The methods lidar_sgm_eval compares, each run on one EvalFrame.

#include <cstdint>
#include <string>

#include "eval/eval_frame.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace evaluation {

enum class MethodKind {
  StereoSgm,       ///< LiDAR-SGM with alpha = 0 and no LiDAR: classic census SGM
  LidarSgm,        ///< LiDAR only (alpha = 1)
  FusedSgm,        ///< LiDAR-SGM, Eq. 5, at `alpha`
  OpenCvSgbm,      ///< cv::StereoSGBM, MODE_SGBM_3WAY, block 5 (the peer)
  Morphological,   ///< IP-Basic-style classical LiDAR-only completion (Ku et al. 2018)
  ThreeCameras,    ///< Triple-SGM: horizontal + vertical census, no LiDAR
  ThreeCamerasLidar,  ///< Triple-SGM fused with the LiDAR at `alpha`
};

struct Method {
  MethodKind kind = MethodKind::StereoSgm;
  double alpha = 0.7;
  std::string name() const;  ///< "stereo-only SGM", "LiDAR-SGM (alpha 0.7)", ...
  bool needsThirdCamera() const { return kind == MethodKind::ThreeCameras || kind == MethodKind::ThreeCamerasLidar; }
};

struct MethodOutput {
  Image<std::int16_t> disparity;  ///< x16, kInvalidDisparity where none
  double milliseconds = 0;
};

/// Runs `method` on `frame` with the project's default parameters (numDisparities from the
/// frame). Throws std::invalid_argument when the frame lacks what the method needs.
MethodOutput runMethod(const Method& method, const EvalFrame& frame, const Parameters& base = {});

}  // namespace evaluation
}  // namespace lidar_sgm
