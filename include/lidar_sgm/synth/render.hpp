#pragma once
/// @file render.hpp  Pinhole cameras that ray-trace the scene: color, exact depth, object mask.

#include <cstdint>
#include <string>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {

/// Weather changes the images only; the geometry, the ground truth and the LiDAR stay the same.
enum class Weather {
  Clear,
  Rain,  ///< overcast, lower contrast and fog, wet mirror-like ground, sensor noise, rain streaks
};
std::string toString(Weather weather);
/// "clear" or "rain"; throws std::invalid_argument naming the accepted values.
Weather weatherFromString(const std::string& name);

/// A rectified pinhole camera looking along +x of the world (KITTI camera axes: x right = -y
/// world, y down = -z world, z forward = +x world). Pixel (u, v) is the centre of the pixel.
struct PinholeCamera {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int width = 0;
  int height = 0;
  double focal = 0;  ///< [px]
  double cx = 0;
  double cy = 0;

  /// The direction's forward component is 1, so the ray parameter of a hit is its depth z.
  Ray pixelRay(double u, double v) const { return {position, {1.0, -(u - cx) / focal, -(v - cy) / focal}}; }
};

struct RenderedView {
  Image<Rgb8> color;              ///< lidar_sgm::Rgb8 (core), what the pipeline takes as color
  Image<float> depth;             ///< z in the camera [m]; 0 for sky (no ground truth, as in KITTI)
  Image<std::uint8_t> objectMask; ///< 1 on cars, poles, signs, trees
};

/// One sample per pixel centre (the ground truth is exact at the pixel centre). `noiseSeed`
/// decorrelates the sensor noise and rain streaks of different cameras.
RenderedView renderView(const Scene& scene, const PinholeCamera& camera, Weather weather, std::uint32_t noiseSeed);

}  // namespace synth
}  // namespace lidar_sgm
