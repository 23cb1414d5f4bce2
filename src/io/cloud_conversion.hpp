#pragma once
/// @file cloud_conversion.hpp  (private) What the cloud readers hand back, made from what they
/// parsed: PCL's blob (any field types and order) or KITTI points, as pcl::PointXYZI.

#include <string>
#include <vector>

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// The blob's points with its width, height and header: x, y, z from float32 or float64 fields,
/// the intensity from "intensity", "reflectance" or "i" (any numeric type; 0 without one).
/// Throws "cannot read cloud '<source>': <problem>" for a missing or integer coordinate, a field
/// outside the point record, or data shorter than the header declares.
pcl::PointCloud<pcl::PointXYZI> toXyzi(const std::string& source, const pcl::PCLPointCloud2& blob);

/// KITTI points as an unorganized cloud (height 1), in order.
pcl::PointCloud<pcl::PointXYZI> toXyzi(const std::vector<KittiPoint>& points);

/// Sets is_dense from the points: it is a promise to downstream code (which may skip NaN
/// checks), so it is computed and never copied from a file header.
void setDenseness(pcl::PointCloud<pcl::PointXYZI>& cloud);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
