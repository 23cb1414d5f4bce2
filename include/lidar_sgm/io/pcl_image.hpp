#pragma once
/// @file pcl_image.hpp  cv::Mat <-> PCL's organized image clouds, for the PCL class.

#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace lidar_sgm {
namespace io {

/// An 8-bit BGR (or gray) cv::Mat as an organized pcl::PointCloud<pcl::RGB> (width x height).
/// Throws std::invalid_argument for an empty image or another depth than 8 bits.
pcl::PointCloud<pcl::RGB> toPclImage(const cv::Mat& image);

}  // namespace io
}  // namespace lidar_sgm
