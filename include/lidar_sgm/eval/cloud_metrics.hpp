#pragma once
/// @file cloud_metrics.hpp  The output scored as a cloud (Tanks and Temples / ETH3D style
/// precision, completeness, F-score) and as a depth map (KITTI depth completion's RMSE, MAE,
/// iRMSE, iMAE); see docs/EVALUATION.md, "Metrics". Both work on depth z = f*b/d, from the
/// method's disparity and the GT disparity, so no point cloud has to be built.

#include <cstdint>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace eval {

/// How a frame's output is scored as a cloud.
struct CloudScoring {
  /// [m] The tools' default (ReprojectionOptions::maxDepth): an estimate beyond it is no point of
  /// the cloud a user gets, and a GT pixel beyond it is not asked for (completeness).
  double maxDepth = 80.0;
  /// [m] The tolerance never falls below this: at a few metres, tau * z would ask for less than
  /// one x16 disparity step can resolve.
  double minTolerance = 0.1;
  /// true where the GT covers every pixel, so GT 0 means "no surface" (sky) and a point there is
  /// wrong (P3 synthetic). false where GT 0 means "not measured" (KITTI, DrivingStereo,
  /// Middlebury's occlusions, held-out LiDAR rings): a point there cannot be judged and is not scored.
  bool denseGroundTruth = false;
};

/// Precision, completeness and F-score at one tau.
struct CloudScore {
  double precision = 0;     ///< correct points / scored points
  double completeness = 0;  ///< GT pixels with a correct point / GT pixels
  double fScore = 0;        ///< harmonic mean of the two (0 when both are 0)
};

/// A point is correct when |z - z_gt| <= max(minTolerance, tau * z_gt).
struct CloudMetrics {
  long points = 0;    ///< scored points: estimates with z <= maxDepth that have GT (or dense GT's "no surface")
  long gtPixels = 0;  ///< GT pixels with z_gt <= maxDepth (completeness's denominator)
  CloudScore tau3;    ///< tau = 3 %
  CloudScore tau5;    ///< tau = 5 % (the headline figure)
};

/// KITTI depth completion's metrics over GT pixels that have an estimate.
struct DepthMetrics {
  long gtPixels = 0;         ///< GT pixels with z_gt <= maxDepth
  long estimatedPixels = 0;  ///< of those, pixels with a point (estimate with z <= maxDepth)
  double rmseMm = 0;         ///< RMS of z - z_gt [mm]
  double maeMm = 0;          ///< mean |z - z_gt| [mm]
  double irmsePerKm = 0;     ///< RMS of 1/z - 1/z_gt [1/km]
  double imaePerKm = 0;      ///< mean |1/z - 1/z_gt| [1/km]
  double density = 0;        ///< estimatedPixels / gtPixels
};

/// `estimate`: x16 disparities (kInvalidDisparity, or <= 0: none). `groundTruth`: disparity [px],
/// <= 0 or NaN = none. `exclude` (optional): non-zero pixels are the LiDAR input and are scored
/// neither as points nor as GT (as in evaluateDisparity: they measure the input, not the method).
/// `focalBaseline`: f*b [px*m]. Throws std::invalid_argument on differing sizes or f*b <= 0.
CloudMetrics evaluateCloud(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                           ImageView<const std::uint8_t> exclude, double focalBaseline,
                           const CloudScoring& scoring = {});

/// Same inputs; only `scoring.maxDepth` is used (GT 0 is never scored here: these metrics are over
/// GT pixels).
DepthMetrics evaluateDepth(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                           ImageView<const std::uint8_t> exclude, double focalBaseline,
                           const CloudScoring& scoring = {});

}  // namespace eval
}  // namespace lidar_sgm
