#pragma once
// A small, exactly known rig for the geometry tests.

#include <cmath>

#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace test {

/// 101x61 image, fx = fy = 100, cx = 50, cy = 30, baseline 0.5 m (f*b = 50 px*m).
/// The LiDAR is KITTI-like: x forward, y left, z up, mounted 0.3 m behind and 0.1 m above
/// the camera, and yawed by 2 degrees so that the rotation is not a pure axis permutation.
inline geometry::StereoCalibration smallRig() {
  geometry::StereoCalibration c;
  c.width = 101;
  c.height = 61;
  c.K << 100, 0, 50, 0, 100, 30, 0, 0, 1;
  c.baseline = 0.5;
  Eigen::Matrix3d axes;  // LiDAR axes in camera coordinates: x_l -> z_c, y_l -> -x_c, z_l -> -y_c
  axes << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  c.T_cam_lidar.linear() = axes * yaw;
  // t is where the LiDAR origin lands in camera coordinates (p_cam = R*0 + t): 0.3 m behind
  // (-z) and 0.1 m above (-y, the camera's y points down).
  c.T_cam_lidar.translation() = Eigen::Vector3d(0.0, -0.1, -0.3);
  return c;
}

/// The LiDAR-frame point that the camera sees at pixel (u, v) at depth z.
inline Eigen::Vector3f lidarPointAt(const geometry::StereoCalibration& c, double u, double v, double z) {
  const Eigen::Vector3d camera((u - c.cx()) * z / c.fx(), (v - c.cy()) * z / c.fy(), z);
  return (c.T_lidar_cam() * camera).cast<float>();
}

}  // namespace test
}  // namespace lidar_sgm
