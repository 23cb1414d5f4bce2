#pragma once
/// @file alpha_sweep.hpp  The sweep of the LiDAR weight alpha (Eq. 5; the paper's Fig. 5): the
/// alphas, the best one, and its plot.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {

/// The paper's alpha: always in the sweep, so that every table has it.
constexpr double kPaperAlpha = 0.7;

/// 0, step, 2*step, ... up to 1 (each rounded to 1e-3, the last clamped to 1), plus kPaperAlpha
/// where the grid misses it; ascending. Throws std::invalid_argument unless step is in (0, 1].
std::vector<double> sweepAlphas(double step);

/// The index of the best point: highest median "correct", then lowest RMSE (first on ties).
/// Throws std::invalid_argument for an empty sweep.
std::size_t bestAlphaIndex(const std::vector<std::pair<double, DisparityMetrics>>& medians);

/// Writes the first sweep of `result` as a PNG at `path`: median correct and RMSE against alpha,
/// side by side. Throws std::invalid_argument when `result` has no sweep.
void writeAlphaSweepPlot(const ProtocolResult& result, const std::string& path);

}  // namespace eval
}  // namespace lidar_sgm
