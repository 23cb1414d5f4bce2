#pragma once
// A frame's calibration, whatever its layout's calibration format.

#include <string>

#include "batch/frame_list.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace apps {

/// KITTI odometry calib.txt (P0..P3, Tr: LiDAR to the rectified camera 0) read as the KITTI
/// object format it is a case of: R0_rect the identity, Tr_velo_to_cam = Tr. `width`/`height`
/// as readKittiCalibration (0 = from the images). Throws std::runtime_error naming the file.
geometry::StereoCalibration readKittiOdometryCalibration(const std::string& path, int width = 0, int height = 0);

/// `frame.calib` read in `frame.calibFormat`.
geometry::StereoCalibration readFrameCalibration(const Frame& frame, int width = 0, int height = 0);

}  // namespace apps
}  // namespace lidar_sgm
