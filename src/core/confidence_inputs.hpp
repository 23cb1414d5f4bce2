#pragma once
// The confidence inputs every backend shares (they need no cost volume): computed by the core
// from the images and the LiDAR support, and the per-pixel combination (confidence.hpp).

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

/// Row buffers of the functions below, kept by the matcher between frames (no allocation once
/// a frame size has been seen).
struct ConfidenceScratch {
  std::vector<int> a, b;
  std::vector<std::uint8_t> bytes;
};

/// g: the Chebyshev distance to the nearest pixel with support != 0, capped at kLidarDistanceCap
/// (also where there is no support at all).
void lidarDistance(ImageView<const std::uint8_t> support, ImageView<std::uint8_t> distance,
                   ConfidenceScratch& scratch);

/// t and s of confidence.hpp; an empty image gives t = 0 and s = 0 everywhere.
void textureAndSaturation(const GrayImageView& image, ImageView<std::uint8_t> texture,
                          ImageView<std::uint8_t> saturated, ConfidenceScratch& scratch);

/// v: max - min of the valid disparities (x16) in the 5x5 window [px], capped at
/// kDisparityRangeCap; 0 where the pixel itself is invalid.
void disparityRange(ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> range,
                    ConfidenceScratch& scratch);

/// The confidence of every pixel: confidenceFromLogit256(confidenceLogit256(...)) of the mode's
/// model, 0 where `disparity` is kInvalidDisparity. `paths`: SGM's path count (c = S1 / paths).
/// LiDAR-only mode reads neither texture, saturation nor the left-right difference.
void combineConfidence(const ConfidenceInputs& inputs, MatchMode mode, int paths,
                       ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> confidence);

}  // namespace lidar_sgm
