#pragma once
// Real frames for the benchmark, read with lidar_sgm::io (OpenCV); built only when io is.

#include <string>

#include "bench_frame.hpp"

namespace lidar_sgm {
namespace bench {

/// KITTI 2015 training frame `id` under `dataRoot`/kitti_stereo2015_training_sample with the
/// LiDAR of protocol P1: eval::simulateLidarFromGroundTruth on its GT with default options,
/// exactly as tests/eval/test_kitti_p1.cpp and lidar_sgm_eval do. Throws std::runtime_error
/// naming what is missing.
Frame loadKittiP1Frame(const std::string& dataRoot, const std::string& id);

/// A rectified pair and a KITTI-format sparse disparity PNG (uint16, disparity*256, 0 = none).
/// Throws std::runtime_error for unreadable files, 16-bit images or mismatched sizes.
Frame loadFileFrame(const std::string& leftPath, const std::string& rightPath, const std::string& lidarPath);

/// `frame` at `width` x `height`: the pair resized with cv::resize (INTER_AREA to shrink, which
/// averages instead of dropping pixels; INTER_LINEAR to enlarge), the LiDAR moved with it.
Frame resizedFrame(const Frame& frame, int width, int height);

}  // namespace bench
}  // namespace lidar_sgm
