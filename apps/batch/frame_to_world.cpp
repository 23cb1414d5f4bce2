#include "batch/frame_to_world.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace lidar_sgm {
namespace apps {

Eigen::Isometry3d readKittiOdometryTr(const std::string& calibPath) {
  std::ifstream in(calibPath);
  if (!in) throw std::invalid_argument("cannot read the calibration '" + calibPath + "'");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Tr:", 0) != 0) continue;
    std::istringstream fields(line.substr(3));
    std::vector<double> numbers;
    for (double value; fields >> value;) numbers.push_back(value);
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    if (numbers.size() != 12 || !fields.eof()) {
      throw std::invalid_argument("'" + calibPath + "': the 'Tr:' line is not 12 numbers");
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) T(r, c) = numbers[static_cast<std::size_t>(4 * r + c)];
    }
    // readKittiOdometryCalibration has checked this rotation already, at the calibration's tolerance.
    Eigen::Isometry3d tr;
    tr.matrix() = T;
    return tr;
  }
  throw std::invalid_argument("'" + calibPath + "' has no 'Tr:' line: not a KITTI odometry calib.txt");
}

Eigen::Isometry3d poseCameraFromLidar(const Frame& frame, const geometry::StereoCalibration& calibration) {
  if (frame.calibFormat == CalibrationFormat::KittiOdometry) return readKittiOdometryTr(frame.calib);
  return calibration.T_cam_lidar;
}

Eigen::Isometry3d cloudToWorld(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& poseCameraFromLidar,
                               const geometry::StereoCalibration& calibration, geometry::OutputFrame cloudFrame) {
  const Eigen::Isometry3d worldFromLidar = pose * poseCameraFromLidar;
  return cloudFrame == geometry::OutputFrame::Camera ? worldFromLidar * calibration.T_lidar_cam() : worldFromLidar;
}

}  // namespace apps
}  // namespace lidar_sgm
