#pragma once
// The merged map seen from above: an orthographic top view with the trajectory drawn on it.

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>

#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace apps {

struct TopViewOptions {
  int maxSide = 2000;             ///< the picture's long side at most [px]
  int margin = 10;                ///< empty border [px]
  double minMetresPerPixel = 0.1; ///< never finer than this (the map's voxel size) [m/px]
};

struct TopView {
  cv::Mat image;                  ///< 8-bit BGR
  double metresPerPixel = 0.0;
};

/// The map's x-z plane (camera 0 of frame 0: x right, z forward up the picture, y down) at one
/// metres-per-pixel scale fit to the extent of the map and the trajectory. Each pixel shows its
/// highest point (smallest y; ties: the earlier point): its color when `useColor`, else a turbo
/// color of its height over the map's height range. The trajectory (world positions, in order)
/// is a white line. Single-threaded, no anti-aliasing: the same map gives the same bytes.
/// Throws std::invalid_argument for an empty map or bad options.
TopView renderTopView(const pcl::PointCloud<PointXYZRGBConfidence>& map, bool useColor,
                      const std::vector<Eigen::Vector3d>& trajectory, const TopViewOptions& options = {});

}  // namespace apps
}  // namespace lidar_sgm
