#pragma once
/// @file calibration.hpp  The rectified stereo rig and its LiDAR: what projection and
/// reprojection need, in one validated value.

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lidar_sgm {
namespace geometry {

/// A rectified stereo rig with a LiDAR, in the project's conventions (README, "Conventions"):
/// metres and pixels; `T_cam_lidar` maps LiDAR points into the rectified left camera,
/// p_cam = T_cam_lidar * p_lidar; disparity d = f*b/z (Eq. 3).
struct StereoCalibration {
  /// How far from orthonormal a rotation read from a file may be.
  static constexpr double kRotationTolerance = 1e-4;
  /// Sane ranges, so that a typo (fx = 1e-300 gave a 3.8e302 m baseline) is an error
  /// and not a cloud: focal lengths [px] of real cameras lie well inside the first, stereo rigs'
  /// baselines [m] (a phone's to a wide survey rig's) inside the second.
  /// Largest image side [px] (io::kMaxImageSide too): a larger frame is refused before any allocation.
  static constexpr int kMaxImageSide = 16384;
  static constexpr double kMinFocalLength = 1.0;
  static constexpr double kMaxFocalLength = 1e6;
  static constexpr double kMinBaseline = 1e-3;
  static constexpr double kMaxBaseline = 100.0;

  int width = 0;                  ///< rectified image size [px]
  int height = 0;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  ///< rectified left intrinsics (fx, fy, cx, cy; no skew)
  double baseline = 0.0;          ///< distance between the rectified cameras [m], > 0
  Eigen::Isometry3d T_cam_lidar = Eigen::Isometry3d::Identity();

  double fx() const { return K(0, 0); }
  double fy() const { return K(1, 1); }
  double cx() const { return K(0, 2); }
  double cy() const { return K(1, 2); }
  /// f*b [px*m]: d = focalBaseline() / z.
  double focalBaseline() const { return K(0, 0) * baseline; }
  Eigen::Isometry3d T_lidar_cam() const { return T_cam_lidar.inverse(); }

  /// Throws std::invalid_argument naming the first problem: non-positive image size, a focal
  /// length or baseline outside its sane range above, a non-finite entry, skew, a K whose last row is not (0 0 1), or a
  /// rotation that is not orthonormal with determinant +1 (max |R^T R - I| entry and
  /// |det R - 1| up to kRotationTolerance: calibration files print about 7 digits).
  void validate() const;
};

/// A one-line, human-readable summary (size, fx, fy, cx, cy, baseline, translation) for logs.
std::string describe(const StereoCalibration& calibration);

}  // namespace geometry
}  // namespace lidar_sgm
