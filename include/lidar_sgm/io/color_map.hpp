#pragma once
/// @file color_map.hpp  The one color map of the project's pictures: OpenCV's turbo, as a table.

#include <array>

#include <opencv2/core.hpp>

namespace lidar_sgm {
namespace io {

/// Turbo's colors for 0..255 (cv::COLORMAP_TURBO), BGR: what cv::applyColorMap gives the
/// disparity pictures, for pictures drawn point by point (cloud previews, the map's picture).
const std::array<cv::Vec3b, 256>& turboColors();

}  // namespace io
}  // namespace lidar_sgm
