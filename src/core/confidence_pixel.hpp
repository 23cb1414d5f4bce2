#pragma once
// The confidence model's per-pixel pieces (confidence.hpp), inline: the core's public functions
// are these, and a backend's row loop includes them so that the compiler can inline the one
// formula instead of the backend copying it.

#include <algorithm>
#include <cstdint>

#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace inline_model {

/// confidencePixel.
inline ConfidencePixel pixel(const ConfidenceInputs& in, MatchMode mode, int paths, int x, int y) {
  const bool lidarOnly = mode == MatchMode::LidarOnly;
  ConfidencePixel p;
  p.margin = in.margin(x, y);
  p.cost = std::min(in.bestCost(x, y) / paths, 255);
  p.leftRight = lidarOnly ? 0 : in.leftRightDifference(x, y);
  p.lidarDistance = in.lidarDistance(x, y);
  p.texture = lidarOnly ? 0 : in.texture(x, y);
  p.saturated = lidarOnly ? 0 : in.saturated(x, y);
  p.disparityRange = in.disparityRange(x, y);
  return p;
}

/// confidenceLogit256: z of confidence.hpp, in 1/256 logit.
inline int logit256(const ConfidenceModel& model, const ConfidencePixel& p) {
  const int noCounterpart = p.leftRight == kNoCounterpartDifference ? 1 : 0;
  const int r = noCounterpart != 0 ? 0 : std::min(p.leftRight, kLeftRightDifferenceCap);
  return model.bias + model.margin * p.margin + model.marginLow * std::min(p.margin, 16) + model.cost * p.cost +
         model.leftRight * r + model.noCounterpart * noCounterpart + model.lidarDistance * p.lidarDistance +
         model.lidarDistanceLow * std::min(p.lidarDistance, 4) + model.texture * p.texture +
         model.textureLow * std::min(p.texture, 8) + model.saturated * p.saturated +
         model.disparityRange * p.disparityRange + model.disparityRangeLow * std::min(p.disparityRange, 2);
}

/// The logistic curve in steps of 1/64 logit, entry i at logit (i - 1024) / 64 (2048 entries).
const std::uint8_t* sigmoidTable();

/// The entry of sigmoidTable() for z: floor division by 4 (1/256 -> 1/64 logit), also for negative z.
inline int tableIndex(int logit256) { return (std::clamp(logit256, -4096, 4095) >> 2) + 1024; }

/// confidenceFromLogit256, with `table` = sigmoidTable().
inline std::uint8_t fromLogit256(const std::uint8_t* table, int logit256) { return table[tableIndex(logit256)]; }

}  // namespace inline_model
}  // namespace lidar_sgm
