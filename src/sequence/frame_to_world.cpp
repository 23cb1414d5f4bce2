#include "lidar_sgm/sequence/frame_to_world.hpp"

#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace sequence {

Eigen::Isometry3d poseCameraFromLidar(const Frame& frame, const geometry::StereoCalibration& calibration) {
  if (frame.calibFormat == CalibrationFormat::KittiOdometry) return io::readKittiOdometryTr(frame.calib);
  return calibration.T_cam_lidar;
}

Eigen::Isometry3d cloudToWorld(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& poseCameraFromLidar,
                               const geometry::StereoCalibration& calibration, geometry::OutputFrame cloudFrame) {
  const Eigen::Isometry3d worldFromLidar = pose * poseCameraFromLidar;
  return cloudFrame == geometry::OutputFrame::Camera ? worldFromLidar * calibration.T_lidar_cam() : worldFromLidar;
}

}  // namespace sequence
}  // namespace lidar_sgm
