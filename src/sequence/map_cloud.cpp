#include "lidar_sgm/sequence/map_cloud.hpp"

#include <stdexcept>

#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/conversions.h>
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace lidar_sgm {
namespace sequence {
namespace {

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name) { return pcl::getFieldIndex(cloud, name) >= 0; }

/// The cloud converted to `PointT` (only fields it has: PCL warns about the others), copied
/// into the map's point type.
template <typename PointT>
void convert(const pcl::PCLPointCloud2& blob, pcl::PointCloud<PointXYZRGBConfidence>& out) {
  pcl::PointCloud<PointT> typed;
  pcl::fromPCLPointCloud2(blob, typed);
  pcl::copyPointCloud(typed, out);
}

template <typename PointT>
void write(const std::string& path, const pcl::PointCloud<PointXYZRGBConfidence>& points, io::CloudFormat format) {
  pcl::PointCloud<PointT> typed;
  pcl::copyPointCloud(points, typed);
  io::writeCloud(path, typed, format);
}

}  // namespace

MapInput readFrameCloud(const std::string& path) {
  const std::string extension = io::lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") {
    throw std::runtime_error("cannot read the cloud '" + path + "' for the map: not a .pcd or .ply file");
  }
  const pcl::PCLPointCloud2 blob = io::readCloudFields(path);
  if (!hasField(blob, "x") || !hasField(blob, "y") || !hasField(blob, "z")) {
    throw std::runtime_error("the cloud '" + path + "' has no x, y, z fields");
  }
  MapInput input;
  input.hasColor = hasField(blob, "rgb") || hasField(blob, "rgba");
  input.hasConfidence = hasField(blob, "confidence");
  if (input.hasColor && input.hasConfidence) {
    convert<PointXYZRGBConfidence>(blob, input.points);
  } else if (input.hasColor) {
    convert<pcl::PointXYZRGB>(blob, input.points);
  } else if (input.hasConfidence) {
    convert<PointXYZConfidence>(blob, input.points);
  } else {
    convert<pcl::PointXYZ>(blob, input.points);
  }
  return input;
}

void writeMapCloud(const std::string& path, const VoxelMap& map, io::CloudFormat format) {
  const pcl::PointCloud<PointXYZRGBConfidence> points = map.points();
  if (map.hasColor() && map.hasConfidence()) {
    write<PointXYZRGBConfidence>(path, points, format);
  } else if (map.hasColor()) {
    write<pcl::PointXYZRGB>(path, points, format);
  } else if (map.hasConfidence()) {
    write<PointXYZConfidence>(path, points, format);
  } else {
    write<pcl::PointXYZ>(path, points, format);
  }
}

}  // namespace sequence
}  // namespace lidar_sgm
