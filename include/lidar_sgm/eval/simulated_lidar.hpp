#pragma once
/// @file simulated_lidar.hpp  Protocol P1: a 64-beam-like sparse LiDAR sampled from dense GT.

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace eval {

/// An HDL-64E-like scanner at the camera: 64 beams evenly spread over +2 .. -24.8 deg elevation.
struct SimulatedLidarOptions {
  double focal = 0;             ///< [px]; <= 0: KITTI's 721.5377 scaled to the image width (1242)
  double principalRow = -1;     ///< c_y [px]; < 0: KITTI's ratio 172.854/375 of the image height
  int beams = 64;
  double elevationTopDeg = 2.0;
  double elevationBottomDeg = -24.8;
  int columnStep = 2;           ///< every 2nd GT pixel along a beam's row
  double noiseSigma = 0.1;      ///< Gaussian disparity noise [px]
  unsigned seed = 1;
};

/// Image rows the beams hit: v = c_y - f*tan(elevation), inside the image, ascending, unique.
std::vector<int> simulatedBeamRows(int width, int height, const SimulatedLidarOptions& options);

/// Samples GT (disparity [px], <= 0 / NaN = none) on the beam rows, adds noise, and marks the
/// sampled pixels in `inputMask` (resized to the GT's size) so that they are not scored.
LidarPoints simulateLidarFromGroundTruth(ImageView<const float> groundTruth,
                                         const SimulatedLidarOptions& options,
                                         Image<std::uint8_t>& inputMask);

}  // namespace eval
}  // namespace lidar_sgm
