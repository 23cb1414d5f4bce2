#pragma once
// A KITTI raw drive's poses from its OXTS packets (the GPS/IMU unit's oxts/data/*.txt), in the
// convention of a -poses file: the calibration's rectified left camera of frame i into frame 0's.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {

/// The values of one OXTS packet: a line of 30 numbers, of which the pose uses the first six.
constexpr std::size_t kOxtsPacketValues = 30;

/// The pose fields of an OXTS packet.
struct OxtsPacket {
  double latitude = 0;   ///< [deg]
  double longitude = 0;  ///< [deg]
  double altitude = 0;   ///< [m]
  double roll = 0;       ///< [rad], about the IMU's x (forward)
  double pitch = 0;      ///< [rad], about y (left)
  double yaw = 0;        ///< [rad], about z (up): the heading, 0 = east, counter-clockwise
};

/// One packet file (oxts/data/NNNNNNNNNN.txt): a line of kOxtsPacketValues numbers "lat lon alt
/// roll pitch yaw vn ve ...". Throws std::invalid_argument naming the file for a file that cannot
/// be read, another count of values, a non-number, a latitude outside (-90, 90) or a longitude
/// outside [-180, 180] degrees, or an angle beyond 2 pi (degrees written as radians).
OxtsPacket readOxtsPacket(const std::string& path);

/// The IMU's poses in the world, relative to the first packet's (the first is the identity), as
/// the KITTI raw devkit's convertOxtsToPose computes them: Mercator coordinates at the scale of the
/// first packet's latitude, the altitude as z, the rotation Rz(yaw) * Ry(pitch) * Rx(roll).
std::vector<Eigen::Isometry3d> imuPosesFromOxts(const std::vector<OxtsPacket>& packets);

/// Each IMU pose (IMU i into IMU 0) as the pose of a camera rigidly mounted on the vehicle:
/// camera i into camera 0, T_cam_imu * T_imu0_imui * T_imu_cam.
std::vector<Eigen::Isometry3d> cameraPosesFromImuPoses(const std::vector<Eigen::Isometry3d>& imuPoses,
                                                       const Eigen::Isometry3d& cameraFromImu);

/// The poses of a KITTI raw drive's frames (each with its Frame::oxts, all of one calibration)
/// from their packets, as a -poses file gives them for this layout: of the calibration's
/// rectified left camera. The IMU reaches the camera through the date folder's
/// calib_imu_to_velo.txt and the frame calibration's T_cam_lidar (calib_velo_to_cam.txt,
/// R_rect_00 and camera 2's offset). Throws std::invalid_argument naming the file for a missing
/// or malformed packet or calibration file.
std::vector<Eigen::Isometry3d> oxtsPosesOfDrive(const std::vector<Frame>& frames);

/// The folder of the drive's packets, for messages ("DRIVE/oxts/data").
std::string oxtsFolderOf(const std::vector<Frame>& frames);

}  // namespace sequence
}  // namespace lidar_sgm
