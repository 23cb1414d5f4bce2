#pragma once
// Radiance of a hit and of the sky, as the camera sees them.

#include "lidar_sgm/synth/render.hpp"

namespace lidar_sgm {
namespace synth {

/// `direction` of the ray in any length; `footprint` the pixel's size on the surface [m].
Rgb shade(const Scene& scene, const Ray& ray, const Hit& hit, Weather weather, double footprint);

Rgb skyColor(const Eigen::Vector3d& direction, Weather weather);

}  // namespace synth
}  // namespace lidar_sgm
