#pragma once
/// @file frame.hpp  One synthetic frame: images, exact ground truth, LiDAR sweep, calibration.
///
/// @code
///   lidar_sgm::synth::FrameOptions options;   // 1242x375, baseline 0.54 m, HDL-64E, clear
///   options.seed = 7;
///   const lidar_sgm::synth::Frame frame = lidar_sgm::synth::renderFrame(options);
///   // frame.left / frame.right (color), frame.disparity (GT, 0 = none), frame.lidar (LiDAR frame)
/// @endcode

#include <cstdint>
#include <string>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/synth/lidar_scan.hpp"
#include "lidar_sgm/synth/render.hpp"
#include "lidar_sgm/synth/rig.hpp"

namespace lidar_sgm {
namespace synth {

struct FrameOptions {
  std::uint32_t seed = 0;       ///< the scene, the LiDAR noise and the rain all follow from it
  Weather weather = Weather::Clear;
  int beams = 64;               ///< 64 (HDL-64E) or 128
  bool thirdCamera = false;     ///< also render the camera 0.20 m above the left one
  double baseline = 0.54;       ///< [m], in [0.05, 2]
  int width = 1242;             ///< [px], in [32, 4096]; intrinsics scale with the size
  int height = 375;             ///< [px], in [32, 4096]
  bool lidarInCameraViewOnly = false;  ///< keep only points that project into the left image
  double lidarRangeNoise = 0.02;  ///< LiDAR range noise sigma [m], in [0, 1]; 0 = exact ranges
  /// Where the rig stands on the road (world frame, StereoRig::origin): x forward along the
  /// street, |y| <= 1 (inside the ego lane), z = 0. A drive moves it along x (see sequence.hpp).
  Eigen::Vector3d rigPosition = Eigen::Vector3d::Zero();
};

/// Throws std::invalid_argument naming the first bad option and its allowed values.
void validate(const FrameOptions& options);

struct Frame {
  StereoRig rig;
  Image<Rgb8> left;
  Image<Rgb8> right;
  Image<Rgb8> up;                 ///< empty without thirdCamera
  Image<float> disparity;         ///< left camera, f*b/z [px]; 0 = no GT (sky)
  Image<float> depth;             ///< left camera z [m]; 0 = no GT (sky)
  Image<std::uint8_t> objectMask; ///< 1 on cars, poles, signs, trees
  std::vector<LidarPoint> lidar;  ///< LiDAR frame (see rig.lidarToCamera)
};

/// Deterministic: the same options give the same frame, bit for bit.
Frame renderFrame(const FrameOptions& options);

/// The frame in a given scene (e.g. one street shared by the frames of a drive); options.seed
/// then only seeds the LiDAR noise, the sensor noise and the rain. renderFrame(options) is
/// renderFrame(makeStreetScene(options.seed), options).
Frame renderFrame(const Scene& scene, const FrameOptions& options);

/// The points whose projection falls inside the left image (in front of the camera).
std::vector<LidarPoint> keepInCameraView(const std::vector<LidarPoint>& points, const StereoRig& rig);

/// The scan projected into the left image as a sparse disparity image (d = f*b/z [px], 0 = no
/// point; the nearest point wins where several share a pixel), like KITTI's projected
/// `velodyne_raw` maps: the input form of `lidar_sgm_disparity -lidar`.
Image<float> projectLidarDisparity(const std::vector<LidarPoint>& points, const StereoRig& rig);

}  // namespace synth
}  // namespace lidar_sgm
