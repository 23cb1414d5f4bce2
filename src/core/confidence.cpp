#include "lidar_sgm/core/confidence.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/confidence_pixel.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace {

// The logistic curve, tabulated once in steps of 1/64 logit: every backend and platform reads
// the same bytes.
std::array<std::uint8_t, 2048> makeSigmoidTable() {
  std::array<std::uint8_t, 2048> table{};
  for (int i = 0; i < 2048; ++i) {
    const double z = (i - 1024) / 64.0;
    table[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::lround(255.0 / (1.0 + std::exp(-z))));
  }
  return table;
}

// Fitted with `lidar_sgm_eval -fit_confidence -out DIR` (logistic regression, IRLS) on the
// synthetic frames of protocol P3 (clear and rain, 64 beams, seeds 300-303), checked on the
// evaluation's frames (seeds 100-104); see docs/RESULTS.md for the reliability.
// Order: bias, m, min(m,16), c, r, n, g, min(g,4), t, min(t,8), s, v, min(v,2) (ConfidenceModel).
constexpr ConfidenceModel kStereoOnly{721, 1, -4, -11, 95, 0, 0, 0, 8, -24, 0, -34, 0};
constexpr ConfidenceModel kLidarOnly{1763, 0, 13, -10, 0, 0, -104, 53, 0, 0, 0, -43, -392};
constexpr ConfidenceModel kFused{1189, 1, -3, 2, -15, 36, -42, -27, -7, 40, 0, -52, -88};

}  // namespace

const ConfidenceModel& confidenceModel(MatchMode mode) {
  switch (mode) {
    case MatchMode::StereoOnly: return kStereoOnly;
    case MatchMode::LidarOnly: return kLidarOnly;
    case MatchMode::Fused: return kFused;
  }
  return kFused;
}

int confidenceLogit256(const ConfidenceModel& model, const ConfidencePixel& p) {
  return inline_model::logit256(model, p);
}

namespace inline_model {

const std::uint8_t* sigmoidTable() {
  static const std::array<std::uint8_t, 2048> table = makeSigmoidTable();
  return table.data();
}

}  // namespace inline_model

std::uint8_t confidenceFromLogit256(int logit256) {
  return inline_model::fromLogit256(inline_model::sigmoidTable(), logit256);
}

}  // namespace lidar_sgm
