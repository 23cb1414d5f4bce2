#include "batch/frame_calibration.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace lidar_sgm {
namespace apps {

geometry::StereoCalibration readKittiOdometryCalibration(const std::string& path, int width, int height) {
  const std::string unreadable = io::unreadableFileReason(path);
  if (!unreadable.empty()) throw std::runtime_error("cannot read the calibration '" + path + "': " + unreadable);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the calibration '" + path + "'");
  // The odometry images are rectified already (R0_rect = I) and Tr maps the LiDAR into the
  // rectified camera 0, which is the object format's R0_rect * Tr_velo_to_cam: the object
  // reader then composes T_cam_lidar for camera 2 from P2 as it does for the object benchmark.
  std::ostringstream objectFormat;
  std::string line;
  bool hasTr = false;
  while (std::getline(in, line)) {
    if (line.rfind("Tr:", 0) == 0) {
      objectFormat << "Tr_velo_to_cam:" << line.substr(3) << '\n';
      hasTr = true;
    } else if (line.rfind("R0_rect:", 0) != 0 && line.rfind("Tr_velo_to_cam:", 0) != 0) {
      objectFormat << line << '\n';
    }
  }
  if (!hasTr) throw std::runtime_error("'" + path + "' has no 'Tr:' line: not a KITTI odometry calib.txt");
  objectFormat << "R0_rect: 1 0 0 0 1 0 0 0 1\n";
  return io::readKittiCalibrationFromString(objectFormat.str(), path, width, height);
}

geometry::StereoCalibration readFrameCalibration(const Frame& frame, int width, int height) {
  if (frame.calibFormat == CalibrationFormat::KittiOdometry) {
    return readKittiOdometryCalibration(frame.calib, width, height);
  }
  return io::readCalibration(frame.calib, width, height);
}

}  // namespace apps
}  // namespace lidar_sgm
