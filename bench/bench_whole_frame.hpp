#pragma once
// The frame as a user of the tools sees it: a KITTI 2015 frame with its raw Velodyne scan through
// Densifier::run with the tools' defaults (projection, matching, confidence, output filters,
// minimum confidence, reprojection to a colored cloud), timed in pairs with OpenCV's StereoSGBM
// on the same pair. Built only with lidar_sgm::io (which brings OpenCV) and the pipeline.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "bench_frame.hpp"
#include "bench_opencv_sgbm.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace bench {

/// A frame's inputs as lidar_sgm_densify reads them: the scan's points (LiDAR frame), the
/// calibration, the pair as gray and the left image's colors.
struct WholeFrame {
  std::vector<Eigen::Vector3f> points;
  geometry::StereoCalibration calibration;
  Frame pair;  ///< the 8-bit gray pair (what OpenCV's SGBM gets too); no LiDAR in it
  Image<Rgb8> color;
};

/// KITTI 2015 training frame `id` ("000007" or "000007_10") of `dataRoot`/kitti2015_lidar: its
/// pair, raw scan and KITTI raw calibration. Throws std::runtime_error naming what is missing.
WholeFrame loadKitti2015LidarFrame(const std::string& dataRoot, const std::string& id);

/// Medians over the timed frames (each its own median) and the pairing with OpenCV.
struct WholeFrameMeasurement {
  double frameMs = 0;      ///< wall clock around Densifier::run
  double projectMs = 0;    ///< DensificationTimings::project
  double matchMs = 0;      ///< DensificationTimings::match: the core's stages and the pipeline's steps around them
  double reprojectMs = 0;  ///< DensificationTimings::reproject
  double witnessMs = 0;    ///< DensificationTimings::witness: part of match, the hidden-LiDAR filter's stereo match
  double kernelMs = 0;     ///< the core's stages (StageTimings::total() - transfers)
  double confidenceMs = 0; ///< StageTimings::confidence: the core's part of the confidence
  double filtersMs = 0;    ///< DensificationTimings::filters: part of match, the passes after the matcher
  PairedTiming paired;     ///< Densifier::run against cv::StereoSGBM::compute, frame by frame
  std::size_t cloudPoints = 0;
  double densifierPeakRssMiB = 0;  ///< the process's peak RSS after three Densifier frames, before any OpenCV run
  int disparities = 0;     ///< the search range used (from the LiDAR by default), in the matched image
  MatchMode mode = MatchMode::Fused;
};

/// Three Densifier frames alone (densifierPeakRssMiB), then
/// `runs` pairs after `warmups`: one Densifier frame (defaults, fused, `backend`, `scale`, and
/// `matcher`'s threads and gated search), then one cv::StereoSGBM::compute with `sgbm` on `sgbmPair`
/// (the pair at the scale matched) with as many threads, each frame after `idleMs` ms of idling
/// (pairWithOpenCvSgbm). Throws std::logic_error if a frame is not fused.
/// `hiddenLidar` false turns the Densifier's hidden-LiDAR filter off (its default is on);
/// `witnessScale` is its witness's scale (HiddenLidarOptions::witnessScale).
WholeFrameMeasurement measureWholeFrame(const WholeFrame& frame, Backend backend, const Parameters& matcher, float scale,
                                        const Frame& sgbmPair, const SgbmSettings& sgbm, int runs, int warmups,
                                        int idleMs, bool hiddenLidar = true, float witnessScale = 0.5f,
                                        bool lidarAnchor = true);

}  // namespace bench
}  // namespace lidar_sgm
