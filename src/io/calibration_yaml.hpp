#pragma once
/// @file calibration_yaml.hpp  (private) Our calibration YAML (width, height, K, baseline,
/// T_cam_lidar, as cv::FileStorage writes it) parsed with yaml-cpp.
///
/// Why not cv::FileStorage: hostile files made OpenCV 4.6's parser hang forever (33 bytes) or ask
/// for 32 GB. yaml-cpp is fuzzed upstream (OSS-Fuzz) and bounds its nesting depth.

#include <string>

#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// The most bytes a calibration YAML may have: ours are about 600.
constexpr std::size_t kMaxCalibrationYamlBytes = 1 << 20;

/// Parses `text` (it must start with "%YAML", as OpenCV writes it). Throws std::runtime_error
/// naming `source` and, where one is at fault, the key: a syntax error (with its line), a missing
/// key, a value of the wrong kind, a matrix of the wrong shape or with a non-finite entry.
geometry::StereoCalibration parseCalibrationYaml(const std::string& text, const std::string& source);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
