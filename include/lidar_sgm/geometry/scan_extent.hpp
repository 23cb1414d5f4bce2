#pragma once
/// @file scan_extent.hpp  Where in the image the scan measured anything.

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace geometry {

/// Invalidates (kInvalidDisparity) the pixels above the highest and below the lowest LiDAR
/// point of their column, with `marginRows` of slack; a column's span is taken over the
/// samples within +-`marginColumns` columns, and a column with no sample there is cleared.
///
/// Why: LiDAR-only SGM fills every pixel, but above the top beam (KITTI: above +2 degrees, the
/// sky and upper facades) nothing was measured; the path costs only carry the top beam's
/// disparity upwards. Returns the number of pixels it invalidated.
std::size_t cropToScanRows(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                           int marginRows, int marginColumns);

}  // namespace geometry
}  // namespace lidar_sgm
