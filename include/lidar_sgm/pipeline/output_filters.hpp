#pragma once
/// @file output_filters.hpp  The filters the Densifier runs between matching and reprojection,
/// so that disparity(), depth(), the disparity files and the cloud agree.

#include <cstddef>

#include "lidar_sgm/pipeline/outlier_filter.hpp"
#include "lidar_sgm/pipeline/sky_mask.hpp"

namespace lidar_sgm {

/// Both run in the modes with LiDAR (fused, LiDAR-only, Triple-SGM with LiDAR): the sky test
/// needs the scan, and stereo-only SGM has its left-right check instead.
struct OutputFilterOptions {
  SkyFilterOptions sky;
  OutlierFilterOptions outliers;
};

/// What the filters removed in the last run, in pixels.
struct OutputFilterStats {
  std::size_t sky = 0;
  std::size_t outliers = 0;
  std::size_t inconsistentLidar = 0;  ///< LiDAR points left out of the matching (lidar_consistency.hpp)
  std::size_t hiddenLidar = 0;        ///< LiDAR points left out of the matching (hidden_lidar.hpp)
  std::size_t anchored = 0;           ///< pixels the LiDAR moved by a sub-pixel amount (lidar_anchor.hpp)
};

}  // namespace lidar_sgm
