#pragma once
// Procedural surface colors (albedo) of the scene's materials.

#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {

/// Albedo at a hit. `footprint` is the size of the pixel on the surface [m]: pattern detail finer
/// than a pixel fades to its mean, as a real lens and sensor would average it, so that the left and
/// right cameras see the same color for the same surface point.
Rgb albedo(const Scene& scene, const Hit& hit, double footprint);

}  // namespace synth
}  // namespace lidar_sgm
