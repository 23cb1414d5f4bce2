#pragma once
/// @file lidar_scan.hpp  A spinning multi-beam LiDAR ray-traced in the scene.

#include <cstdint>
#include <vector>

#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {

/// A point as KITTI's velodyne .bin stores it: LiDAR frame (x forward, y left, z up) [m],
/// intensity in [0, 1].
struct LidarPoint {
  float x = 0;
  float y = 0;
  float z = 0;
  float intensity = 0;
};

struct LidarOptions {
  int beams = 64;
  double elevationTopDeg = 2.0;      ///< beams evenly spread from top to bottom
  double elevationBottomDeg = -24.8;
  double azimuthStepDeg = 0.08;
  /// Only the front half (azimuth -90..+90 deg) is scanned: the cameras see nothing behind, and
  /// it halves the rays.
  double azimuthHalfRangeDeg = 90.0;
  double maxRange = 120.0;           ///< [m]
  double minRange = 0.9;
  double rangeNoiseSigma = 0.02;     ///< [m]

  /// Velodyne HDL-64E as in KITTI: 64 beams, +2 .. -24.8 deg, 0.08 deg steps, 120 m.
  static LidarOptions hdl64();
  /// A 128-beam sensor (Ouster OS1-128 / Hesai-like): +15 .. -25 deg, 0.1 deg steps, 245 m.
  static LidarOptions beams128();
  /// hdl64() for 64, beams128() for 128; throws std::invalid_argument otherwise.
  static LidarOptions forBeams(int beams);
};

/// One sweep from `position` (world frame; the LiDAR's axes are the world's). Ranges get Gaussian
/// noise; returns drop out on dark and on specular surfaces and at grazing angles. Points come
/// column by column (azimuth from +90 to -90 deg), top beam first.
std::vector<LidarPoint> scanLidar(const Scene& scene, const Eigen::Vector3d& position, const LidarOptions& options,
                                  std::uint32_t seed);

}  // namespace synth
}  // namespace lidar_sgm
