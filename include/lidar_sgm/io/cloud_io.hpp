#pragma once
/// @file cloud_io.hpp  Point cloud files: KITTI velodyne .bin, PCD and PLY in; PCD (binary,
/// binary-compressed or ASCII) and PLY (binary or ASCII) out (PCL io).

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

/// How writeCloud encodes the points. Measured on a 424k-point XYZRGB KITTI cloud (README,
/// "Output formats"): binary PCD 6 ms / 6.8 MB, binary-compressed 140-190 ms / 6.6 MB, ASCII
/// about 1 s / 18 MB.
enum class CloudFormat {
  Binary,      ///< PCD "DATA binary" (fields packed, no padding) or PLY binary_little_endian: the fastest
  Compressed,  ///< PCD "DATA binary_compressed" (PCL's LZF): barely smaller for dense clouds, ~25x slower
  Ascii,       ///< text, 9 significant digits so that floats read back exactly: the slowest, largest
};

/// "binary", "compressed", "ascii".
std::string toString(CloudFormat format);
/// The inverse of toString(); std::invalid_argument naming the accepted names otherwise.
CloudFormat cloudFormatFromString(const std::string& name);

/// Throws std::invalid_argument when `path` cannot be written as `format`: an extension other
/// than .pcd or .ply (case-insensitive), or Compressed for a PLY file (PLY has no compressed
/// form). For callers that check their outputs before doing any work; writeCloud checks too.
void checkCloudOutput(const std::string& path, CloudFormat format);

/// Writes by extension (.pcd or .ply) in `format` (default: binary, the fastest). The file is
/// written to a temporary name in the same directory and renamed over `path` only when
/// complete. Throws std::runtime_error naming the file (also for a path checkCloudOutput refuses).
void writeCloud(const std::string& path, const pcl::PCLPointCloud2& cloud, CloudFormat format = CloudFormat::Binary);

template <typename PointT>
void writeCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud, CloudFormat format = CloudFormat::Binary) {
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  writeCloud(path, blob, format);
}

}  // namespace io
}  // namespace lidar_sgm
