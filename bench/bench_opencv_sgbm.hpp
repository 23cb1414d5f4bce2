#pragma once
// The peer: OpenCV's cv::StereoSGBM timed on the same pair, the same way; built only with OpenCV.

#include <functional>
#include <string>

#include "bench_frame.hpp"

namespace lidar_sgm {
namespace bench {

/// cv::StereoSGBM's settings: MODE_SGBM_3WAY, block 5, and OpenCV's usual penalties for gray
/// images (P1 = 8*5*5, P2 = 32*5*5); the rest as lidar_sgm_eval's SGBM baseline (OpenCV's
/// stereo_match sample), so the bench times what the evaluation scores.
struct SgbmSettings {
  int numDisparities = 128;
  int blockSize = 5;
  int P1 = 8 * 5 * 5;
  int P2 = 32 * 5 * 5;
  int disp12MaxDiff = 1;
  int preFilterCap = 63;
  int uniquenessRatio = 10;
  int speckleWindowSize = 100;
  int speckleRange = 32;
};

/// One line naming every setting and the OpenCV version, for the settings block.
std::string describe(const SgbmSettings& settings);

/// Median milliseconds of cv::StereoSGBM::compute on the frame's pair over `runs` frames after
/// `warmups`, with OpenCV limited to `threads` threads (>= 1).
double timeOpenCvSgbm(const Frame& frame, const SgbmSettings& settings, int threads, int runs, int warmups);

/// Ours against OpenCV frame by frame: `runs` pairs (after `warmups` of each), one of our frames
/// (`ours`) then one of cv::StereoSGBM, so that both see the same machine state; the ratio is
/// taken per pair. On a shared VM whose speed drifts by 10-30 % between minutes, separate medians
/// measured one after the other are not comparable; pairs are. Each frame of either starts after
/// `idleMs` milliseconds of idling (kPairIdleMs in the bench), so that neither runs beside the
/// other's workers still spinning after their last frame.
struct PairedTiming {
  double oursMs = 0;   ///< median of our frames
  double sgbmMs = 0;   ///< median of OpenCV's frames
  double ratio = 0;    ///< median of ours / OpenCV over the pairs
  double ratioMin = 0;
  double ratioMax = 0;
};
PairedTiming pairWithOpenCvSgbm(const Frame& frame, const SgbmSettings& settings, int threads,
                                const std::function<void()>& ours, int runs, int warmups, int idleMs);

}  // namespace bench
}  // namespace lidar_sgm
