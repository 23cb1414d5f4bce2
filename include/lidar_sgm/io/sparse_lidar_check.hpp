#pragma once
/// @file sparse_lidar_check.hpp  Whether a sparse LiDAR image holds what its option says.
///
/// KITTI writes disparities and depths in one format (uint16 PNG, value*256, 0 = none), so a
/// depth map given where disparities are expected (or the other way round) reads without error
/// and gives a wrong result. Its values tell the two apart: a road scene's disparity grows toward
/// the bottom of the image, where the ground is near, and its depth shrinks there.

#include <cstdint>
#include <string>
#include <vector>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace io {

/// What the file's values (and name) say.
struct SparseLidarCheck {
  std::string error;                  ///< values that cannot be what the option expects
  std::vector<std::string> warnings;  ///< values or a name that look like the other kind
};

/// A sparse image read as disparities (x16, kInvalidDisparity = none) for an image of
/// `imageWidth` columns: a disparity of imageWidth or more cannot be (an error); a file named
/// like a depth map ("depth" without "disp" in its name, or in the nearest of its 3 folders
/// that says either) or whose values shrink toward the bottom rows (rowTrend below 0.8) looks
/// like a depth map (warnings).
SparseLidarCheck checkSparseDisparity(const std::string& path, ImageView<const std::int16_t> disparity16,
                                      int imageWidth);

/// A sparse image read as depths and converted to disparities (x16): a file named like a
/// disparity map ("disp" in its name) or whose converted disparities shrink toward the bottom
/// rows looks like a disparity map (warnings).
SparseLidarCheck checkSparseDepth(const std::string& path, ImageView<const std::int16_t> disparity16);

/// The median value of the valid pixels in the bottom third of the rows that hold any, over the
/// median in the top third; 0 when either third has fewer than 100 valid pixels (no verdict).
/// Road scenes give 1.3-6.0 (the 29 frames of kitti2015_lidar projected), their depths read as
/// disparities 0.16-0.75.
double rowTrend(ImageView<const std::int16_t> disparity16);

}  // namespace io
}  // namespace lidar_sgm
