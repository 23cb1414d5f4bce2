#pragma once
/// @file min_confidence.hpp  The pipeline's last step: pixels below a minimum confidence go.

#include <cstdint>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

/// The integer form of "confidence / 255 >= minConfidence": confidence >= ceil(255 * minConfidence).
/// Throws std::invalid_argument for minConfidence outside [0, 1].
int confidenceThreshold(double minConfidence);

/// Drops (kInvalidDisparity, confidence 0) every pixel whose confidence is below `minConfidence`
/// in [0, 1] (0 keeps every pixel): Densifier's last step, and what the evaluation applies to
/// score what the tools ship. Same sizes required (std::invalid_argument otherwise).
void applyMinConfidence(ImageView<std::int16_t> disparity, ImageView<std::uint8_t> confidence, double minConfidence);

}  // namespace lidar_sgm
