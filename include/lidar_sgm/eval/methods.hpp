#pragma once
// The methods lidar_sgm_eval compares, each run on one EvalFrame.

#include <cstdint>
#include <string>

#include "eval/eval_frame.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"
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

/// Runs `method` on `frame`: the LiDAR-SGM methods with `base` (the tools' SGM options, scale and
/// threads included) on `backend`, alpha the method's and numDisparities the frame's (rounded
/// up to a multiple of 32 at scale 0.5, which needs one). The baselines ignore `base`. Throws
/// std::invalid_argument when the frame lacks what the method needs.
MethodOutput runMethod(const Method& method, const EvalFrame& frame, const Parameters& base = {},
                       Backend backend = Backend::Auto);

/// The search range of a frame whose protocol chose `frameNumDisparities`, at `scale`: the
/// same at scale 1; at 0.5 rounded up to a multiple of 32 (the half-scale search range must be
/// a multiple of 16), at most 512.
int numDisparitiesAt(int frameNumDisparities, float scale);

}  // namespace evaluation
}  // namespace lidar_sgm
