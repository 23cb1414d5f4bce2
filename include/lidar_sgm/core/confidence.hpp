#pragma once
/// @file confidence.hpp  Per-pixel confidence of a disparity: close to the probability that the
/// pixel is correct (KITTI's criterion: error <= 3 px or <= 5 %), from what the matcher has.
///
/// Inputs per pixel (each an integer, so every backend gives the same bytes):
///  - m, the peak-ratio margin of the aggregated cost curve: (S2 - S1) / S2 in 1/256, S1 the winner's
///    cost, S2 the lowest cost more than 1 px away from it (a flat or double minimum -> 0);
///  - c, the winner's cost per path: min(255, S1 / paths) (a poor match everywhere -> high);
///  - r, the left-right difference |d_left - d_right| [px], capped at 8, and n = 1 where there is no
///    right counterpart (x - d outside the image: occluded border);
///  - g, the distance to the nearest LiDAR support [px, Chebyshev, capped at kLidarDistanceCap;
///    0 = a point touches the pixel's 3x3 neighbourhood; the cap in stereo-only mode];
///  - t, the local texture: mean |I(x+1) - I(x-1)| over a 5x5 window, 8-bit units, capped at 255
///    (16-bit images are scaled by 1/256); s = 1 where the pixel is saturated (8-bit >= 250);
///  - v, the local disparity range: max - min of the valid disparities in the 5x5 window [px],
///    capped at 16 (depth edges, where SGM smears foreground into background: flying points).
/// The confidence is a logistic model of them, one weight set per mode:
///   z = b + w_m*m + w_m16*min(m, 16) + w_c*c + w_r*r + w_n*n + w_g*g + w_g4*min(g, 4) + w_t*t
///       + w_t8*min(t, 8) + w_s*s + w_v*v + w_v2*min(v, 2)
///   confidence = 255 / (1 + exp(-z / 256)), rounded; 0 where there is no disparity.
/// Weights are integers in 1/256 of a logit, fitted by logistic regression on synthetic frames with
/// exact ground truth (lidar_sgm_eval -fit_confidence) and checked with a reliability diagram on
/// held-out frames (docs/RESULTS.md). LiDAR-only mode uses neither the images nor the left-right
/// difference (its result must not depend on whether a left image is given).

#include <cstdint>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

enum class MatchMode;

/// Cap of the LiDAR distance input [px]: KITTI's HDL-64E leaves gaps of 4-6 rows between beams,
/// so 16 tells "between two beams" from "above or below the scan".
constexpr int kLidarDistanceCap = 16;
/// The left-right difference of a pixel whose right counterpart x - d lies outside the image, or
/// whose right view has no winner.
constexpr std::uint8_t kNoCounterpartDifference = 255;
/// Cap of the left-right difference input [px].
constexpr int kLeftRightDifferenceCap = 8;
/// Cap of the local disparity range input [px].
constexpr int kDisparityRangeCap = 16;

/// The confidence below which the pipeline (Densifier, the tools) drops a pixel by default, in
/// [0, 1]: keep a pixel when it is more likely right than wrong. Chosen on the measured
/// precision/completeness curves (docs/RESULTS.md): the highest threshold that keeps the fused
/// cloud's completeness >= 93 % on P3 clear 64 beams (0.6 drops it to 92.97 %).
constexpr double kDefaultMinConfidence = 0.5;

/// The inputs of the last frame, at the size the frame was matched at (half size at scale 0.5).
struct ConfidenceInputs {
  Image<std::uint8_t> margin;               ///< m (0 where there is no winner)
  Image<std::uint16_t> bestCost;            ///< S1 (c = min(255, S1 / paths))
  Image<std::uint8_t> leftRightDifference;  ///< |d_l - d_r| capped at 254, 255 = no counterpart
  Image<std::uint8_t> lidarDistance;        ///< g
  Image<std::uint8_t> texture;              ///< t
  Image<std::uint8_t> saturated;            ///< s
  Image<std::uint8_t> disparityRange;       ///< v
};

/// One pixel's inputs, as the model reads them.
struct ConfidencePixel {
  int margin = 0, cost = 0, leftRight = 0, lidarDistance = 0, texture = 0, saturated = 0, disparityRange = 0;
};

/// Logistic weights, in 1/256 of a logit per unit of each input.
struct ConfidenceModel {
  int bias = 0;
  int margin = 0;          ///< w_m
  int marginLow = 0;       ///< w_m16, on min(m, 16): the steep part near an ambiguous minimum
  int cost = 0;            ///< w_c
  int leftRight = 0;       ///< w_r, on min(r, kLeftRightDifferenceCap)
  int noCounterpart = 0;   ///< w_n
  int lidarDistance = 0;   ///< w_g
  int lidarDistanceLow = 0;  ///< w_g4, on min(g, 4): between beams
  int texture = 0;         ///< w_t
  int textureLow = 0;      ///< w_t8, on min(t, 8)
  int saturated = 0;       ///< w_s
  int disparityRange = 0;  ///< w_v
  int disparityRangeLow = 0;  ///< w_v2, on min(v, 2)
};

/// The fitted model of `mode` (the values and how they were fitted: confidence.cpp).
const ConfidenceModel& confidenceModel(MatchMode mode);

/// Pixel (x, y) of `inputs` as the model of `mode` reads them (LiDAR-only: r, t, s = 0);
/// `paths`: SGM's path count.
ConfidencePixel confidencePixel(const ConfidenceInputs& inputs, MatchMode mode, int paths, int x, int y);

/// The model's logit z (1/256 units) for one pixel.
int confidenceLogit256(const ConfidenceModel& model, const ConfidencePixel& pixel);

/// 255 / (1 + exp(-z / 256)), rounded; z is clamped to [-4096, 4095] (|logit| <= 16).
std::uint8_t confidenceFromLogit256(int logit256);

}  // namespace lidar_sgm
