#pragma once
/// @file rig.hpp  The sensor rig: a rectified stereo pair, an optional third camera above the left
/// one, and a LiDAR mounted behind and above them (like KITTI's), plus its KITTI calibration text.

#include <string>

#include <Eigen/Geometry>

#include "lidar_sgm/synth/render.hpp"

namespace lidar_sgm {
namespace synth {

struct StereoRig {
  int width = 1242;
  int height = 375;
  double focal = 721.5377;     ///< KITTI's rectified focal length [px] at 1242 px
  double cx = 609.5593;
  double cy = 172.854;
  double baseline = 0.54;      ///< [m], right camera to the right of the left one
  double cameraHeight = 1.65;  ///< left camera above the road [m]
  double thirdCameraOffset = 0.20;  ///< third camera above the left one, same orientation [m]
  /// LiDAR origin relative to the left camera, world axes: 0.27 m behind, 0.08 m above (KITTI).
  Eigen::Vector3d lidarOffset{-0.27, 0.0, 0.08};
  /// Where the rig stands on the road (world frame, z = 0): the origin for a single frame, x =
  /// index * step along a drive. The sensors keep the world's orientation: the car drives straight.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();

  /// KITTI's intrinsics scaled to `width` x `height` (f and cx with the width, cy with the height).
  static StereoRig kittiLike(int width, int height, double baseline);

  Eigen::Vector3d leftPosition() const { return origin + Eigen::Vector3d{0.0, 0.0, cameraHeight}; }
  Eigen::Vector3d lidarPosition() const { return leftPosition() + lidarOffset; }
  PinholeCamera left() const;
  PinholeCamera right() const;
  PinholeCamera up() const;

  /// A LiDAR-frame point (x forward, y left, z up) in the left camera's KITTI axes (x right,
  /// y down, z forward): the transform written as Tr_velo_to_cam.
  Eigen::Vector3d lidarToCamera(const Eigen::Vector3d& lidarPoint) const;

  /// The left camera's KITTI axes (x right, y down, z forward; origin at the camera) into the
  /// world frame (x forward, y left, z up): world = R * camera + leftPosition().
  Eigen::Isometry3d worldFromLeftCamera() const;
};

/// KITTI object-benchmark calibration: P0..P3 (P2 = left, P3 = right with P3[0][3] = -f*b; P0 and P1
/// equal P2 and P3, as this rig has no separate gray cameras), R0_rect = I, Tr_velo_to_cam,
/// Tr_imu_to_velo = [I|0] (no IMU), and `P_up:` for the third camera when `withThirdCamera`.
std::string kittiCalibrationText(const StereoRig& rig, bool withThirdCamera);

/// KITTI odometry `calib.txt`: P0..P3 as above and `Tr:` (the LiDAR into the rectified camera 0,
/// which is the left camera here), plus `P_up:` when `withThirdCamera`.
std::string kittiOdometryCalibrationText(const StereoRig& rig, bool withThirdCamera);

}  // namespace synth
}  // namespace lidar_sgm
