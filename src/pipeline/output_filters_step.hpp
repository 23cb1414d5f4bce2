#pragma once
// The Densifier's filter step between matching and reprojection.

#include <vector>

#include "lidar_sgm/pipeline/output_filters.hpp"

namespace lidar_sgm {

/// Sky first (it removes whole runs from the top of a column), then the isolated points, some of
/// which the sky removal leaves behind at the border of the removed region.
inline OutputFilterStats applyOutputFilters(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                                            const GrayImageView& left, const OutputFilterOptions& options) {
  OutputFilterStats stats;
  stats.sky = removeSky(disparity16, samples, left, options.sky);
  stats.outliers = removeOutliers(disparity16, options.outliers);
  return stats;
}

}  // namespace lidar_sgm
