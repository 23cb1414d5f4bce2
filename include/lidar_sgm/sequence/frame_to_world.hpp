#pragma once
// Where a frame's dense cloud lies in the map's world: the pose camera of frame 0.

#include <string>

#include <Eigen/Geometry>

#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace sequence {

/// T_pose_lidar: the LiDAR into the camera the poses refer to. KITTI odometry's poses are of
/// camera 0 (the rectified reference camera, whose P0 has no offset), while the calibration's
/// T_cam_lidar ends in camera 2, the left camera of the color pair we match (frame_calibration
/// composes [I | K^-1 P2[:,3]] onto Tr): so for a KittiOdometry frame this is calib.txt's Tr.
/// Any other layout has no camera 0 of its own: its poses (-poses) are taken to be of the
/// calibration's rectified left camera, T_cam_lidar.
Eigen::Isometry3d poseCameraFromLidar(const Frame& frame, const geometry::StereoCalibration& calibration);

/// The transform taking the points of a dense cloud written in `cloudFrame` into the world:
/// T_world_pose * T_pose_lidar, after T_lidar_cam when the cloud is in the camera frame
/// (geometry::OutputFrame::Camera: the calibration's rectified left camera).
Eigen::Isometry3d cloudToWorld(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& poseCameraFromLidar,
                               const geometry::StereoCalibration& calibration, geometry::OutputFrame cloudFrame);

}  // namespace sequence
}  // namespace lidar_sgm
