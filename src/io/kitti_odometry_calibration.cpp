// KITTI odometry's calib.txt: the object format without R0_rect, its LiDAR transform named "Tr".
#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace lidar_sgm {
namespace io {
namespace {

/// The file's lines, or std::runtime_error naming why it cannot be read.
std::vector<std::string> linesOf(const std::string& path) {
  const std::string unreadable = unreadableFileReason(path);
  if (!unreadable.empty()) throw std::runtime_error("cannot read the calibration '" + path + "': " + unreadable);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the calibration '" + path + "'");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

[[noreturn]] void noTr(const std::string& path) {
  throw std::runtime_error("'" + path + "' has no 'Tr:' line: not a KITTI odometry calib.txt");
}

}  // namespace

geometry::StereoCalibration readKittiOdometryCalibration(const std::string& path, int width, int height) {
  // The odometry images are rectified already (R0_rect = I) and Tr maps the LiDAR into the
  // rectified camera 0, which is the object format's R0_rect * Tr_velo_to_cam: the object
  // reader then composes T_cam_lidar for camera 2 from P2 as it does for the object benchmark.
  std::ostringstream objectFormat;
  bool hasTr = false;
  for (const std::string& line : linesOf(path)) {
    if (line.rfind("Tr:", 0) == 0) {
      objectFormat << "Tr_velo_to_cam:" << line.substr(3) << '\n';
      hasTr = true;
    } else if (line.rfind("R0_rect:", 0) != 0 && line.rfind("Tr_velo_to_cam:", 0) != 0) {
      objectFormat << line << '\n';
    }
  }
  if (!hasTr) noTr(path);
  objectFormat << "R0_rect: 1 0 0 0 1 0 0 0 1\n";
  return readKittiCalibrationFromString(objectFormat.str(), path, width, height);
}

Eigen::Isometry3d readKittiOdometryTr(const std::string& path) {
  // Only the numbers: readKittiOdometryCalibration, which every user of a frame calls first,
  // checks the rotation at the calibration's tolerance.
  for (const std::string& line : linesOf(path)) {
    if (line.rfind("Tr:", 0) != 0) continue;
    std::istringstream fields(line.substr(3));
    std::vector<double> numbers;
    for (double value; fields >> value;) numbers.push_back(value);
    if (numbers.size() != 12 || !fields.eof()) {
      throw std::runtime_error("'" + path + "': the 'Tr:' line is not 12 numbers");
    }
    Eigen::Isometry3d tr = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) tr.matrix()(r, c) = numbers[static_cast<std::size_t>(4 * r + c)];
    }
    return tr;
  }
  noTr(path);
}

}  // namespace io
}  // namespace lidar_sgm
