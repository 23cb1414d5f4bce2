#pragma once
// One frame of an evaluation protocol: what every method gets, and what it is scored against.

#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace eval {

struct EvalFrame {
  std::string protocol;  ///< "P1", "P2", "P3", "KITTI142"
  std::string dataset;   ///< e.g. "kitti2015", "kitti_lidar", "synth_clear_64"
  std::string name;      ///< frame id, unique within the dataset
  cv::Mat left;          ///< rectified left, gray, 8 or 16 bit (what the matchers see)
  cv::Mat right;         ///< rectified right, same size and depth
  cv::Mat leftColor;     ///< 8-bit BGR, for pictures
  cv::Mat up;            ///< optional third camera above the left one (gray, same depth); empty if none
  double upBaselineRatio = 0.0;     ///< b_up / b (the third camera's baseline over the stereo baseline)
  LidarPoints lidar;                ///< the LiDAR input (several points per pixel allowed)
  Image<std::int16_t> lidarSparse;  ///< the same input, one x16 disparity per pixel (nearest), kInvalidDisparity elsewhere
  Image<float> groundTruth;         ///< disparity [px], 0 = no GT
  /// true where the GT covers every pixel, so its 0 means "no surface" (sky), not "not measured":
  /// the cloud metrics then count a point there as wrong (CloudScoring::denseGroundTruth).
  bool denseGroundTruth = false;
  Image<std::uint8_t> exclude;      ///< 1 where a pixel is a LiDAR input pixel (not scored), same size
  /// KITTI 2015's object map where the protocol has one: 0 background, k > 0 foreground object k
  /// (the paper's Table II splits the error by it); empty otherwise.
  Image<std::uint8_t> objectMap;
  /// 1 where an input point projects, for protocols that score those pixels too (exclude empty):
  /// "correct" is then also given on the GT pixels no input point covers. Empty otherwise.
  Image<std::uint8_t> inputPixels;
  double focalBaseline = 0.0;       ///< f*b [px*m], for depth <-> disparity (IP-Basic works on depth)
  /// The rectified rig, where the protocol scores the methods' clouds in 3D against the GT's
  /// cloud (KITTI142, ground_truth_cloud.hpp); empty otherwise.
  std::optional<geometry::StereoCalibration> calibration;
  int numDisparities = 128;         ///< search range for this frame (multiple of 16)
};

}  // namespace eval
}  // namespace lidar_sgm
