#include "lidar_sgm/sequence/frame_calibration.hpp"

#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace sequence {

geometry::StereoCalibration readFrameCalibration(const Frame& frame, int width, int height) {
  if (frame.calibFormat == CalibrationFormat::KittiOdometry) {
    return io::readKittiOdometryCalibration(frame.calib, width, height);
  }
  // KITTI raw's pair carries its image size (S_rect_02): width and height are not needed.
  if (frame.calibFormat == CalibrationFormat::KittiRawPair) {
    return io::readKittiRawCalibration(frame.calib, frame.veloToCam);
  }
  return io::readCalibration(frame.calib, width, height);
}

}  // namespace sequence
}  // namespace lidar_sgm
