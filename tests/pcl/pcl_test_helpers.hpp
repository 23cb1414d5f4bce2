#pragma once
// A small rig and a wall scan for the SGMDensification tests: a scene whose result is known.

#include <cmath>
#include <cstdint>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/type_traits.h>

#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace test {

/// 160x96 image, fx = fy = 200, baseline 0.5 m: f*b = 100, so a wall at 4 m has d = 25 px.
/// The LiDAR mounting is the geometry tests' (KITTI-like, 0.3 m behind, 0.1 m above, 2 deg yaw).
inline geometry::StereoCalibration pclRig() {
  geometry::StereoCalibration c = smallRig();
  c.width = 160;
  c.height = 96;
  c.K << 200, 0, 80, 0, 200, 48, 0, 0, 1;
  c.baseline = 0.5;
  return c;
}

constexpr double kWallDepth = 4.0;

/// The intensity wallScan gives the point at pixel (u, v): far from any gray value (0..255).
inline float wallIntensity(int u, int v) { return static_cast<float>(1000 + v * 1000 + u); }

/// A LiDAR-like scan of a wall at 4 m (left part) and one at 50 m (right of column 120): every
/// 2nd column, every 4th row; intensity (where the type has it) = wallIntensity(u, v).
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr wallScan(const geometry::StereoCalibration& c, bool farRight = false) {
  typename pcl::PointCloud<PointT>::Ptr scan(new pcl::PointCloud<PointT>);
  for (int v = 2; v < c.height; v += 4) {
    for (int u = 0; u < c.width; u += 2) {
      const Eigen::Vector3f p = lidarPointAt(c, u, v, farRight && u > 120 ? 50.0 : kWallDepth);
      PointT q;
      q.x = p.x();
      q.y = p.y();
      q.z = p.z();
      if constexpr (pcl::traits::has_intensity_v<PointT>) q.intensity = wallIntensity(u, v);
      scan->push_back(q);
    }
  }
  scan->header.frame_id = "velodyne";
  scan->header.stamp = 1234567;
  return scan;
}

/// The depth of a LiDAR-frame point seen from the left camera.
inline double cameraDepth(const geometry::StereoCalibration& c, const Eigen::Vector3f& p) {
  return (c.T_cam_lidar * p.cast<double>()).z();
}

/// A color image whose color encodes the pixel: r = x, g = y, b = 7.
inline pcl::PointCloud<pcl::RGB> pixelCodedImage(int width, int height) {
  pcl::PointCloud<pcl::RGB> image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at(x, y).r = static_cast<std::uint8_t>(x);
      image.at(x, y).g = static_cast<std::uint8_t>(y);
      image.at(x, y).b = 7;
    }
  }
  return image;
}

/// The gray of pixelCodedImage at (x, y), computed here in floating point with BT.601's
/// weights (0.299, 0.587, 0.114) rather than with the class's fixed-point formula.
inline float pixelCodedGray(int x, int y) { return static_cast<float>(std::lround(0.299 * x + 0.587 * y + 0.114 * 7)); }

}  // namespace test
}  // namespace lidar_sgm
