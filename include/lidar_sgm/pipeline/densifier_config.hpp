#pragma once
/// @file densifier_config.hpp  Everything a front end can set on a Densifier, in one value, and its
/// one validation. The tools, the Python module, SGMDensification and the evaluation all fill a
/// DensifierConfig (by hand or from the option table of config_options.hpp) and hand it over
/// whole, so that no per-frame setting survives from one use to the next by accident.

#include <string>

#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/geometry/disparity_range.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/pipeline/hidden_lidar.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"
#include "lidar_sgm/pipeline/lidar_consistency.hpp"
#include "lidar_sgm/pipeline/min_confidence.hpp"
#include "lidar_sgm/pipeline/output_filters.hpp"

namespace lidar_sgm {

/// Where a run's disparity search range comes from.
enum class DisparityRangeMode {
  /// From the frame's projected LiDAR (geometry::disparityRangeFromLidar): minDisparity 0,
  /// numDisparities covering the nearest surface the scan saw. A frame without LiDAR points
  /// (stereo-only) keeps the fixed range of the matcher's parameters.
  FromLidar,
  /// The matcher's minDisparity / numDisparities as given (the paper: [0, 128)).
  Fixed,
};

/// "lidar" or "fixed" (the option -disparity_range's words).
std::string toString(DisparityRangeMode mode);

/// The Densifier's whole configuration. Default-constructed it is the shipped default of every
/// front end (the tools' and Python's defaults are read from it).
struct DensifierConfig {
  /// The matcher's parameters (the paper's P1, P2, alpha, sigma ...). Their minDisparity /
  /// numDisparities are the fixed range: used as given with DisparityRangeMode::Fixed, and with
  /// FromLidar only for frames without LiDAR.
  Parameters matcher;
  Backend backend = Backend::Auto;
  DisparityRangeMode rangeMode = DisparityRangeMode::FromLidar;
  geometry::DisparityRangeRule rangeRule;  ///< FromLidar's margin and limits
  geometry::ProjectionOptions projection;  ///< scan -> image, with the occlusion filter
  geometry::ReprojectionOptions reprojection;  ///< disparity -> depth and points
  /// LiDAR-only mode: clear the pixels above the scan's top and below its bottom point per
  /// column (+- lidarCoverageRows rows, +-2 columns), where nothing was measured.
  bool cropToScan = true;
  /// Pixels whose confidence (core/confidence.hpp) is below this, in [0, 1], are dropped from the
  /// disparity, depth and cloud alike; 0 keeps every pixel. Needs matcher.confidence when > 0.
  double minConfidence = kDefaultMinConfidence;
  /// The sky and outlier filters between matching and reprojection (modes with LiDAR).
  OutputFilterOptions filters;
  /// Fused modes: the LiDAR points the stereo pair contradicts are left out of the matching.
  LidarConsistencyOptions lidarConsistency;
  /// Fused modes: the LiDAR points a stereo-only match sees a nearer surface in front of are left
  /// out of the matching.
  HiddenLidarOptions hiddenLidar;
  /// Modes with LiDAR: the far scene's sub-pixel disparity anchored to the agreeing LiDAR points.
  LidarAnchorOptions lidarAnchor;
  /// Refuse a stereo pair that looks swapped (pair_orientation.hpp) instead of matching it.
  bool pairCheck = true;
  /// Also fill the depth image and the dense cloud; off, a run stops at the disparity.
  bool computeCloud = true;
};

/// An empty string when `config` is valid; otherwise a message naming the first offending
/// setting (by its option name where it has one), its value and what is allowed.
std::string validationError(const DensifierConfig& config);

/// Throws std::invalid_argument with validationError() when `config` is invalid.
void validate(const DensifierConfig& config);

}  // namespace lidar_sgm
