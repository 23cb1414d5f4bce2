#include "lidar_sgm/sequence/frame_calibration.hpp"

#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace sequence {

geometry::StereoCalibration readFrameCalibration(const Frame& frame, int width, int height) {
  if (frame.calibFormat == CalibrationFormat::KittiOdometry) {
    return io::readKittiOdometryCalibration(frame.calib, width, height);
  }
  return io::readCalibration(frame.calib, width, height);
}

}  // namespace sequence
}  // namespace lidar_sgm
