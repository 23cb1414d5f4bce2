#pragma once
/// @file cloud_io.hpp  Point cloud files: KITTI velodyne .bin, PCD and PLY in; PCD
/// (binary-compressed) and PLY (binary) out (PCL io).

#include <string>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace lidar_sgm {
namespace io {

/// KITTI velodyne scan: float32 little-endian x, y, z, reflectance per point. Throws
/// std::runtime_error naming the file when it is missing, or when its size is not a multiple of
/// 16 bytes (a truncated file is never read in part). An empty file gives an empty cloud.
pcl::PointCloud<pcl::PointXYZI> readKittiBin(const std::string& path);

/// PCD (ASCII, binary or binary-compressed) or PLY with at least x, y, z fields (float or
/// double); intensity is read when there is an "intensity" (or PLY "reflectance") field,
/// else 0. RGB fields are accepted and ignored. Throws std::runtime_error naming the file for a
/// missing or unreadable file or missing x/y/z fields.
pcl::PointCloud<pcl::PointXYZI> readPcdOrPly(const std::string& path);

/// Picks the reader from the extension: .bin, .pcd, .ply (case-insensitive); any other
/// extension is an error naming the accepted ones.
pcl::PointCloud<pcl::PointXYZI> readCloud(const std::string& path);

/// Writes by extension: .pcd -> binary-compressed PCD, .ply -> binary PLY; any other extension
/// is an error. The file is written to a temporary name in the same directory and renamed over
/// `path` only when complete. Throws std::runtime_error naming the file.
void writeCloud(const std::string& path, const pcl::PCLPointCloud2& cloud);

template <typename PointT>
void writeCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud) {
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  writeCloud(path, blob);
}

}  // namespace io
}  // namespace lidar_sgm
