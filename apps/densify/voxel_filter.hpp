#pragma once
// -voxel: a dense cloud down-sampled to one point per voxel with pcl::VoxelGrid (the centroid of
// the voxel's points, every field averaged: color, confidence), for users who keep every frame of
// a drive and want a tenth of the bytes.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <pcl/common/common.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>

// The project's own point types (confidence) are not among PCL's precompiled instantiations.
#include <pcl/filters/impl/voxel_grid.hpp>
#include <pcl/impl/pcl_base.hpp>

namespace lidar_sgm {
namespace apps {

/// Down-samples `cloud` in place to voxels of edge `leaf` metres (0: unchanged). The output is
/// unorganized, in pcl::VoxelGrid's order (by voxel index), the same bytes for the same cloud.
/// pcl::VoxelGrid copies its input unchanged (with a console warning only) when the voxel
/// indices of the cloud's extent would overflow 32 bits; that is refused here with a message
/// instead, so that -voxel never silently does nothing.
template <typename PointT>
void voxelDownsample(pcl::PointCloud<PointT>& cloud, double leaf) {
  if (leaf <= 0.0 || cloud.empty()) return;
  PointT lo;
  PointT hi;
  pcl::getMinMax3D(cloud, lo, hi);
  const double cells = (std::floor((double{hi.x} - lo.x) / leaf) + 1) * (std::floor((double{hi.y} - lo.y) / leaf) + 1) *
                       (std::floor((double{hi.z} - lo.z) / leaf) + 1);
  if (!(cells < static_cast<double>(std::numeric_limits<std::int32_t>::max()))) {
    throw std::invalid_argument("option -voxel: " + std::to_string(leaf) +
                                " m is too small for this cloud's extent (pcl::VoxelGrid's voxel index "
                                "would overflow); use a larger -voxel or a smaller -max_depth");
  }
  typename pcl::PointCloud<PointT>::Ptr input(new pcl::PointCloud<PointT>);
  input->swap(cloud);
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(input);
  const float edge = static_cast<float>(leaf);
  grid.setLeafSize(edge, edge, edge);
  grid.filter(cloud);
}

}  // namespace apps
}  // namespace lidar_sgm
