#pragma once
// Rain on the sensor: noise and streaks, added to the finished 8-bit image.

#include <cstdint>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/synth/render.hpp"

namespace lidar_sgm {
namespace synth {

/// Gaussian sensor noise and short bright slanted streaks (drops falling during the exposure);
/// `seed` differs per camera, so each camera gets its own drops.
void addRainToImage(Image<Rgb8>& image, std::uint32_t seed);

}  // namespace synth
}  // namespace lidar_sgm
