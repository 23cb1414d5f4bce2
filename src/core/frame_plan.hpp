#pragma once
// What one compute() call asks of a backend, decided once by the core from the parameters and
// the inputs given: every backend executes the same plan instead of re-deriving it, so that a
// rule (when the left-right check runs, which range is searched at half scale) has one home.

#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {

struct FramePlan {
  MatchMode mode = MatchMode::StereoOnly;

  /// The paper's half-scale mode (Sec. IV-F): the core matches 2x2-averaged inputs
  /// (half_scale.hpp) and brings the disparity back to full resolution; the backend never rescales.
  bool halfScale = false;
  int width = 0;   ///< the size matched at: the frame's, or its half-scale size
  int height = 0;

  /// The parameters to match with: the caller's at full scale; at half scale the halved search
  /// range (numDisparities, minDisparity, disp12MaxDiff) and scale 1.
  Parameters params;
  /// The cost range: disparities minDisparity .. minDisparity + D - 1 (params' values).
  int minDisparity = 0;
  int D = 0;

  /// The cameras whose census costs take part: 0 (LiDAR-only), 2 (left/right: C_S) or 3 (with
  /// the up camera: C_S3, Triple-SGM).
  int cameras = 0;
  int ratio16 = 0;  ///< the up camera's baselineRatio16(b_up / b); 0 without it
  /// 1 for the 62-bit 9x7 census, 2 for the 31-bit centre-symmetric one (its cost counts twice).
  int censusScale = 1;

  bool useLidar = false;       ///< C_L from the LiDAR points (LiDAR-only and fused mode)
  int alphaWeight = 0;         ///< Eq. 5's fixed alpha out of 256 (fixed_point.hpp)
  bool adaptiveAlpha = false;  ///< fused with AlphaMode::Adaptive: per-pixel weights (lidarWeights)

  bool lrCheck = false;  ///< the left-right check runs (stereo-only: lrCheck; fused: also lrCheckWithLidar)
  /// Fused mode: the check spares the pixels the LiDAR covers (lidarCoverage) and keeps those
  /// without a counterpart in the right image, which the LiDAR may have measured; stereo-only
  /// has no such witness and drops them.
  bool lrCheckTrustsLidar = false;

  /// Each pixel searches its LiDAR window only (Parameters::gatedSearch, lidarSearchWindows):
  /// fused frames only; stereo-only and LiDAR-only frames keep the full range.
  bool gatedSearch = false;

  bool confidence = false;    ///< the backend computes the peak-ratio margin and S1
  bool confidenceLr = false;  ///< ... and the left-right difference (there is no right view in LiDAR-only mode)

  bool useCameras() const { return cameras > 0; }
  bool upCamera() const { return cameras == 3; }
};

/// The plan of a validated frame of width x height in `mode`; `upBaselineRatio` is b_up / b with
/// an up camera, 0 without one.
FramePlan planFrame(const Parameters& params, MatchMode mode, int width, int height, double upBaselineRatio);

}  // namespace lidar_sgm
