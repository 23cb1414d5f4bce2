#pragma once
/// @file kitti_bin.hpp  KITTI velodyne scans (.bin) without PCL: the points as stored, for code
/// that needs only the points (projection, ring recovery, numpy arrays). cloud_io.hpp's
/// readKittiBin gives the same points as a pcl::PointCloud<pcl::PointXYZI>.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lidar_sgm/io/cloud_limits.hpp"

namespace lidar_sgm {
namespace io {

/// One point of a KITTI velodyne scan, as stored: x, y, z [m] in the LiDAR frame and the
/// reflectance.
struct KittiPoint {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float intensity = 0.0f;  ///< the reflectance, as stored
};

/// KITTI velodyne scan: float32 little-endian x, y, z, reflectance per point (read so on any
/// host), in file order. Values are kept as stored, NaN and Inf included: the caller decides what
/// a non-finite point means (readKittiBin marks its cloud as not dense). Throws
/// std::runtime_error "cannot read cloud '<path>': <problem>" when the file is missing or not a
/// regular file, when its size is not a multiple of 16 bytes (a truncated file is never read in
/// part), or when it holds more than `maxPoints` points (checked from its size, before reading).
/// An empty file gives no points.
std::vector<KittiPoint> readKittiScan(const std::string& path, std::uint64_t maxPoints = kMaxCloudPoints);

/// The same checks and points as readKittiScan, handed over a block of records at a time so the
/// caller fills its own container (a pcl::PointCloud, say) without the whole file in memory
/// beside it: `begin(points)` once with the file's point count before any block, then
/// `block(points, count)` in file order. Returns the point count.
std::size_t readKittiScanBlocks(const std::string& path, std::uint64_t maxPoints,
                                const std::function<void(std::size_t points)>& begin,
                                const std::function<void(const KittiPoint* points, std::size_t count)>& block);

/// The same from the file's bytes already in memory (`size` bytes at `data`, at most
/// kMaxCloudPoints points); `source` names them in messages.
std::vector<KittiPoint> readKittiScanFromBuffer(const void* data, std::size_t size,
                                                const std::string& source = "<buffer>");

}  // namespace io
}  // namespace lidar_sgm
