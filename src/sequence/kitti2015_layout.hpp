#pragma once
// KITTI stereo 2015 training with the raw Velodyne scans beside it (the LiDAR-SGM paper's
// benchmark): its own file because its calibration comes in two forms, each needing checks.

#include <filesystem>
#include <vector>

#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {
namespace detail {

/// Whether `dir` is read as KITTI stereo 2015: a velodyne/ folder with KITTI 2015's calibration
/// beside it (the per-frame calib_cam_to_cam/ or calib_velo_to_cam/ folder, or the shared
/// calib/calib_cam_to_cam.txt or calib/calib_velo_to_cam.txt), or whose scans are named as KITTI
/// 2015 frames (NNNNNN_10), whatever calibration there is: then a missing one is named as such.
bool isKittiStereo2015(const std::filesystem::path& dir);

/// Its frames (see framesFromDirectory()). Throws std::invalid_argument naming the files looked
/// for when there is no calibration, or half of a pair.
std::vector<Frame> kittiStereo2015Frames(const std::filesystem::path& dir);

}  // namespace detail
}  // namespace sequence
}  // namespace lidar_sgm
