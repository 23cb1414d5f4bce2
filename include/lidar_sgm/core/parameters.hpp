#pragma once
/// @file parameters.hpp  The matcher's parameters, with the paper's defaults, and their validation.

#include <string>

namespace lidar_sgm {

/// Census window variants (the paper's stereo cost C_S).
enum class CensusType {
  Census9x7,               ///< 62 bits: every pixel of the 9x7 window against the centre.
  CenterSymmetric9x7,      ///< 31 bits: pixel pairs mirrored about the centre (half the work).
};

/// How the LiDAR weight of Eq. 5 is chosen for each pixel.
enum class AlphaMode {
  Fixed,     ///< alpha everywhere (the paper)
  Adaptive,  ///< more LiDAR weight near the scan's points and in a dense scan
};

/// Parameter names follow OpenCV's StereoSGBM where they mean the same thing.
/// Every value is checked by validate(); nothing is silently coerced.
struct Parameters {
  int minDisparity = 0;       ///< smallest disparity searched [px], in [-512, 512]
  int numDisparities = 128;   ///< search range [px], a multiple of 16 in [16, 512]
  int P1 = 10;                ///< penalty for a disparity change of 1 px between neighbours (Eq. 1)
  int P2 = 100;               ///< penalty for larger jumps (Eq. 1), P1 < P2 <= 4000
  int paths = 4;              ///< SGM paths: 4 (horizontal + vertical, as the paper) or 8 (+ diagonals)
  float alpha = 0.7f;         ///< LiDAR weight in C = alpha*C_L + (1-alpha)*C_S (Eq. 5), in [0, 1]
  /// Fixed: alpha at every pixel (the paper). Adaptive (range-adaptive fusion, the paper's future
  /// work): the stereo share 1 - alpha is scaled per pixel by the distance to the nearest LiDAR
  /// point (1/8 at 0-1 px, rising linearly to 1 at 8 px and beyond) and by the frame's scan density
  /// (1 for a 64-beam-like scan, down to 1/4 for a dense one), so alpha is the weight far from a
  /// sparse scan (src/backends/common/lidar_weights.hpp; measured in docs/RESULTS.md).
  AlphaMode alphaMode = AlphaMode::Fixed;
  float sigma = 2.0f;         ///< std-dev of a LiDAR disparity [px] (Eq. 4), in [0.1, 100]
  /// Upper bound of C_L (Eq. 4). Default 62 = the largest census cost, so that alpha weighs two
  /// costs of the same range and a wrong LiDAR point (seen by the LiDAR, hidden from the camera)
  /// can never outweigh a complete census mismatch. In [1, 255].
  int lidarCostCap = 62;
  /// Pixels that no LiDAR point touches (no point in their 3x3 neighbourhood) have no LiDAR
  /// information. true: they keep the full stereo cost (C = C_S), so the fusion does not weaken
  /// stereo where the LiDAR is blind (e.g. above the scan); false: the paper's literal
  /// C = (1-alpha)*C_S with C_L = 0 there.
  /// Measured on KITTI 2015 (protocol P1, 2 frames): false gives 96.1/94.8 % correct, true
  /// 92.0/92.2 %, so the paper's form is the default.
  bool stereoCostWithoutLidar = false;
  int uniquenessRatio = 0;    ///< margin [%] by which the best cost must beat the others (0 = off), in [0, 99]
  bool lrCheck = true;        ///< left-right consistency check in stereo-only mode
  /// The left-right check in fused mode too. Off by default: measured with lidar_sgm_eval
  /// (every protocol, docs/RESULTS.md), the check in fused mode removes 1-10 % of the pixels
  /// and lowers "correct" everywhere (KITTI P1: 97.58 -> 98.84 % correct without it, P2 real
  /// LiDAR: 91.66 -> 93.05 %), because a missing estimate counts as wrong and the LiDAR cost
  /// already anchors the pixels the check would doubt. Turn it on to trade density for fewer
  /// outliers (KITTI P1, median D1_est: 0.70 % instead of 1.16 % of the estimates wrong).
  bool lrCheckWithLidar = false;
  /// Largest accepted left-right difference [px], in [0, numDisparities]. 2, not OpenCV's
  /// customary 1: stereo-only on the KITTI 2015 frames with LiDAR (docs/RESULTS.md) goes from
  /// 86.5 % correct at 88.8 % density to 90.6 % at 92.4 % (error among the estimates 2.98 ->
  /// 3.24 %), and every P1-P3 group gains 1-5 points of "correct" (its cloud precision loses
  /// 0.3-0.7). Fused mode does not check by default, so it does not change there.
  int disp12MaxDiff = 2;
  /// Fused mode with lrCheckWithLidar: the left-right check spares pixels with a LiDAR point within +-1 column and
  /// +-lidarCoverageRows rows (measured, between beams) — the LiDAR vouches for them, and the
  /// check would only cost density there. 6 rows bridge an HDL-64E's beam gaps in KITTI
  /// images. In [1, 64].
  int lidarCoverageRows = 6;
  /// LiDAR-gated disparity search of fused frames: the LiDAR narrows the stereo search (tSGM's
  /// prior). A pixel with a LiDAR point within +-1 column and +-gatedSearchRows rows searches only
  /// [min - gatedSearchMargin, max + gatedSearchMargin] of those points' disparities, widened to a
  /// multiple of 16 and kept inside [minDisparity, minDisparity + numDisparities); every other
  /// pixel searches the full range. The cost volume and the path sums hold only the windows
  /// (backends/common/lidar_search_windows.hpp). Stereo-only frames have no LiDAR to gate with,
  /// and LiDAR-only frames keep the full range too: their cost is the LiDAR's own, and the gate
  /// measured worse there on simulated LiDAR (docs/RESULTS.md, "LiDAR-gated search"). On by
  /// default; implemented by every backend (cpu_ref, cpu, cuda).
  bool gatedSearch = true;
  /// Widening of a gated window beyond its LiDAR disparities on each side [px], in [0, 512]; like
  /// gatedSearchRows, in the pixels of the matched image (halved images at scale 0.5).
  int gatedSearchMargin = 12;
  int gatedSearchRows = 6;    ///< rows above and below a pixel whose LiDAR points gate it, in [0, 64]
  int medianSize = 5;         ///< median filter window: 0 (off), 3 or 5 (the paper uses 5)
  bool subpixel = true;       ///< parabola fit through the best cost and its two neighbours
  CensusType censusType = CensusType::Census9x7;
  /// Image scale the frame is matched at: 1 (full resolution) or 0.5 (the paper's half-scale
  /// mode, Sec. IV-F). At 0.5 the images are box-averaged 2x2, the LiDAR disparities halved,
  /// numDisparities/2 and minDisparity/2 searched (so numDisparities must be a multiple of 32 and
  /// minDisparity even), and the disparity is brought back to full resolution (values x2, each
  /// half-scale pixel covering its 2x2 block). P1, P2 and sigma keep their values, in the pixels
  /// of the matched image.
  float scale = 1.0f;
  /// Also compute the per-pixel confidence (Matcher::confidence(), core/confidence.hpp): the
  /// peak-ratio margin and the left-right difference in the backend, the rest in the core.
  bool confidence = true;
  /// Worker threads of the fast backends: 0 = the machine's hardware threads. Never changes the
  /// result (fixed partitions; every backend is bit-identical for any count). In [0, 256].
  int threads = 0;
};

/// The number of threads `params.threads` asks for: the hardware's count when it is 0.
int effectiveThreads(const Parameters& params);

/// An empty string when `params` is valid; otherwise a message that names the first offending
/// parameter, its value and its allowed range.
std::string validationError(const Parameters& params);

/// Throws std::invalid_argument with validationError() when `params` is invalid.
void validate(const Parameters& params);

std::string toString(CensusType type);
std::string toString(AlphaMode mode);  ///< "fixed" or "adaptive"
/// "fixed" or "adaptive"; std::invalid_argument naming the text otherwise.
AlphaMode alphaModeFromString(const std::string& text);

}  // namespace lidar_sgm
