#pragma once
/// @file methods.hpp  The methods the evaluation compares, each run on one EvalFrame. Every
/// LiDAR-SGM method runs through lidar_sgm::Densifier, as the tools do, so what is measured is
/// what they ship; the baselines (OpenCV SGBM, IP-Basic) are run directly.

#include <cstdint>
#include <string>
#include <vector>

#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/pipeline/densifier_config.hpp"
#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/pipeline/output_filters.hpp"
#include "lidar_sgm/eval/eval_frame.hpp"
#include "lidar_sgm/geometry/disparity_range.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace eval {

enum class MethodKind {
  StereoSgm,       ///< LiDAR-SGM with alpha = 0 and no LiDAR: classic census SGM
  LidarSgm,        ///< LiDAR only (alpha = 1), cropped to the scan as lidar_sgm_densify ships it
  FusedSgm,        ///< LiDAR-SGM, Eq. 5, at `alpha`
  OpenCvSgbm,      ///< cv::StereoSGBM, MODE_SGBM_3WAY, block 5 (the peer)
  Morphological,   ///< IP-Basic-style classical LiDAR-only completion (Ku et al. 2018)
  ThreeCameras,    ///< Triple-SGM: horizontal + vertical census, no LiDAR
  ThreeCamerasLidar,  ///< Triple-SGM fused with the LiDAR at `alpha`
};

/// Every kind, in the order of the enum.
const std::vector<MethodKind>& allMethodKinds();

/// The stable short id of a kind, for options and JSON: "stereo_sgm", "lidar_sgm", "fused_sgm",
/// "opencv_sgbm", "ip_basic", "triple_sgm", "triple_fused_sgm". Never changes with the wording
/// of the reports.
const char* methodId(MethodKind kind);
/// The kind whose methodId is `id`; throws std::invalid_argument listing the ids otherwise.
MethodKind methodKindFromId(const std::string& id);

struct Method {
  MethodKind kind = MethodKind::StereoSgm;
  double alpha = 0.7;  ///< the LiDAR weight of FusedSgm and ThreeCamerasLidar; ignored by the others
  bool needsThirdCamera() const { return kind == MethodKind::ThreeCameras || kind == MethodKind::ThreeCamerasLidar; }
  /// Whether `alpha` is part of what the method is (FusedSgm, ThreeCamerasLidar).
  bool usesAlpha() const { return kind == MethodKind::FusedSgm || kind == MethodKind::ThreeCamerasLidar; }
};

/// Same kind, and the same alpha where the kind uses one.
bool sameMethod(const Method& a, const Method& b);

/// For reports and plots only: "stereo-only SGM", "LiDAR-SGM (alpha 0.7)", ...
std::string displayName(const Method& method);

struct MethodOutput {
  Image<std::int16_t> disparity;  ///< x16, kInvalidDisparity where none
  /// LiDAR-SGM methods: the Densifier's confidence and disparity before the minimum confidence
  /// dropped any pixel (`disparity` is `allDisparity` with dropBelowConfidence applied, exactly
  /// the Densifier's own last step); empty for the baselines, which have no confidence.
  Image<std::uint8_t> confidence;
  Image<std::int16_t> allDisparity;
  /// LiDAR-SGM methods: the inputs of the confidence, at the matched size.
  ConfidenceInputs confidenceInputs;
  double milliseconds = 0;
  /// The search range the method matched with (the Densifier's usedDisparityRange for the
  /// LiDAR-SGM methods, the frame's for OpenCV SGBM); numDisparities 0 for IP-Basic.
  geometry::DisparityRange range{0, 0};
};

/// Runs `method` on `frame`: the LiDAR-SGM methods through a Densifier (runProjected on the
/// frame's LiDAR, no cloud) configured with `config` (what the tools ship by default; the
/// evaluation tool reads it from the same options), alpha the method's. The search range follows
/// config.rangeMode; its fixed part is `fixedNumDisparities`, or the frame's
/// (EvalFrame::numDisparities) when 0, rounded up to a multiple of 32 at scale 0.5. The baselines
/// ignore `config` (OpenCV SGBM searches the frame's numDisparities). Throws
/// std::invalid_argument when the frame lacks what the method needs.
MethodOutput runMethod(const Method& method, const EvalFrame& frame, const DensifierConfig& config = {},
                       int fixedNumDisparities = 0);

/// The search range of a frame whose protocol chose `frameNumDisparities`, at `scale`: the
/// same at scale 1; at 0.5 rounded up to a multiple of 32 (the half-scale search range must be
/// a multiple of 16), at most 512.
int numDisparitiesAt(int frameNumDisparities, float scale);

}  // namespace eval
}  // namespace lidar_sgm
