#pragma once
// A frame's calibration, whatever its layout's calibration format.

#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {

/// `frame.calib` read in `frame.calibFormat` (io::readCalibration, io::readKittiOdometryCalibration,
/// or io::readKittiRawCalibration with `frame.veloToCam`); `width`/`height` as those (0 = from the
/// images; KITTI raw's files give their own).
geometry::StereoCalibration readFrameCalibration(const Frame& frame, int width = 0, int height = 0);

}  // namespace sequence
}  // namespace lidar_sgm
