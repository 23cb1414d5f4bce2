// The cloud readers of cloud_io.hpp: the format by extension, PCD and PLY from files and buffers
// (through our parsers, pcd_reader.hpp and ply_reader.hpp), KITTI .bin through the PCL-free
// reader (kitti_bin.hpp); each as pcl::PointXYZI (cloud_conversion.hpp).
#include "lidar_sgm/io/cloud_io.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cloud_conversion.hpp"
#include "cloud_file.hpp"
#include "cloud_read_error.hpp"
#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"
#include "pcd_reader.hpp"
#include "ply_reader.hpp"

namespace lidar_sgm {
namespace io {
namespace {

pcl::PointCloud<pcl::PointXYZI> pcdFromBytes(const std::string& source, const unsigned char* data, std::size_t size,
                                             std::uint64_t maxPoints = kMaxCloudPoints) {
  const detail::PcdContent content = detail::parsePcd(source, data, size, maxPoints);
  pcl::PointCloud<pcl::PointXYZI> cloud = detail::toXyzi(source, content.blob);
  cloud.sensor_origin_ = content.origin;
  cloud.sensor_orientation_ = content.orientation;
  return cloud;
}

// PCL's organized PLY: the vertices hold the valid points only, the range grid puts them in
// place; an empty cell is a NaN point, as PCL's reader makes it.
pcl::PointCloud<pcl::PointXYZI> plyFromBytes(const std::string& source, const unsigned char* data, std::size_t size,
                                             std::uint64_t maxPoints = kMaxCloudPoints) {
  const detail::PlyContent content = detail::parsePly(source, data, size, maxPoints);
  pcl::PointCloud<pcl::PointXYZI> vertices = detail::toXyzi(source, content.blob);
  if (content.grid.empty()) return vertices;
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.resize(content.grid.size());
  cloud.width = content.gridWidth;
  cloud.height = content.gridHeight;
  for (std::size_t i = 0; i < content.grid.size(); ++i) {
    pcl::PointXYZI& p = cloud.points[i];
    if (content.grid[i] >= 0) {
      p = vertices.points[static_cast<std::size_t>(content.grid[i])];
    } else {
      p.x = p.y = p.z = p.intensity = std::numeric_limits<float>::quiet_NaN();
    }
  }
  detail::setDenseness(cloud);
  return cloud;
}

// The buffer readers' one check of their arguments.
void requireBufferBytes(const void* data, std::size_t size, const std::string& source) {
  if (size == 0) detail::failCloudRead(source, "the buffer is empty");
  if (data == nullptr) detail::failCloudRead(source, "null data pointer for " + std::to_string(size) + " bytes");
}

}  // namespace

pcl::PointCloud<pcl::PointXYZI> readKittiBin(const std::string& path, std::uint64_t maxPoints) {
  // Straight into the cloud, a block at a time: no copy of the file or of the points.
  pcl::PointCloud<pcl::PointXYZI> cloud;
  readKittiScanBlocks(
      path, maxPoints, [&cloud](std::size_t total) { reserveOnHugePages(cloud.points, total); },
      [&cloud](const KittiPoint* block, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
          cloud.points.emplace_back(block[i].x, block[i].y, block[i].z, block[i].intensity);
        }
      });
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  detail::setDenseness(cloud);
  return cloud;
}

pcl::PointCloud<pcl::PointXYZI> readKittiBinFromBuffer(const void* data, std::size_t size,
                                                       const std::string& source) {
  return detail::toXyzi(readKittiScanFromBuffer(data, size, source));
}

pcl::PointCloud<pcl::PointXYZI> readPcdFromBuffer(const void* data, std::size_t size, const std::string& source) {
  requireBufferBytes(data, size, source);
  return pcdFromBytes(source, static_cast<const unsigned char*>(data), size);
}

pcl::PointCloud<pcl::PointXYZI> readPlyFromBuffer(const void* data, std::size_t size, const std::string& source) {
  requireBufferBytes(data, size, source);
  return plyFromBytes(source, static_cast<const unsigned char*>(data), size);
}

pcl::PointCloud<pcl::PointXYZI> readPcdOrPly(const std::string& path, std::uint64_t maxPoints) {
  detail::requireReadableCloudFile(path);
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") detail::failCloudRead(path, "expected a .pcd or .ply file");
  const std::uint64_t size = detail::cloudFileSize(path);
  if (size == 0) detail::failCloudRead(path, "the file is empty");
  const std::vector<unsigned char> bytes = detail::readCloudFileBytes(path, size);
  if (extension == ".pcd") return pcdFromBytes(path, bytes.data(), bytes.size(), maxPoints);
  return plyFromBytes(path, bytes.data(), bytes.size(), maxPoints);
}

pcl::PointCloud<pcl::PointXYZI> readCloud(const std::string& path, std::uint64_t maxPoints) {
  const std::string extension = lowerExtension(path);
  if (extension == ".bin") return readKittiBin(path, maxPoints);
  if (extension == ".pcd" || extension == ".ply") return readPcdOrPly(path, maxPoints);
  detail::failCloudRead(path, "unsupported extension '" + extension + "' (accepted: .bin, .pcd, .ply)");
}

}  // namespace io
}  // namespace lidar_sgm
