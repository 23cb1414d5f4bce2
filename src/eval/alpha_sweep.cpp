#include "lidar_sgm/eval/alpha_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "lidar_sgm/io/image_io.hpp"
#include "plots.hpp"

namespace lidar_sgm {
namespace eval {

std::vector<double> sweepAlphas(double step) {
  if (!(step > 0.0 && step <= 1.0)) throw std::invalid_argument("alpha sweep step: must be in (0, 1]");
  std::vector<double> alphas;
  // Rounded so that 0.1 * 7 is the paper's 0.7, not 0.7000000000000001.
  for (int i = 0; i * step <= 1.0 + 1e-9; ++i) alphas.push_back(std::min(1.0, std::round(i * step * 1000) / 1000));
  if (std::find_if(alphas.begin(), alphas.end(), [](double a) { return std::abs(a - kPaperAlpha) < 1e-9; }) ==
      alphas.end()) {
    alphas.push_back(kPaperAlpha);
    std::sort(alphas.begin(), alphas.end());
  }
  return alphas;
}

std::size_t bestAlphaIndex(const std::vector<std::pair<double, DisparityMetrics>>& medians) {
  if (medians.empty()) throw std::invalid_argument("bestAlphaIndex: the sweep is empty");
  std::size_t best = 0;
  for (std::size_t a = 1; a < medians.size(); ++a) {
    const DisparityMetrics& m = medians[a].second;
    const DisparityMetrics& b = medians[best].second;
    if (m.correct > b.correct + 1e-12 || (std::abs(m.correct - b.correct) <= 1e-12 && m.rmse < b.rmse)) best = a;
  }
  return best;
}

void writeAlphaSweepPlot(const ProtocolResult& result, const std::string& path) {
  if (result.sweeps.empty()) throw std::invalid_argument("writeAlphaSweepPlot: " + result.protocol + " has no sweep");
  PlotSeries correct{"fused: correct [%]", {}, {}, cv::Scalar(180, 119, 31), {}};
  PlotSeries rmse{"fused: RMSE [px]", {}, {}, cv::Scalar(14, 127, 255), {}};
  for (const auto& [alpha, m] : result.sweeps.front().medians) {
    correct.x.push_back(alpha);
    correct.y.push_back(100.0 * m.correct);
    rmse.x.push_back(alpha);
    rmse.y.push_back(m.rmse);
  }
  PlotSpec left;
  left.title = result.protocol + ": correct vs alpha (median)";
  left.xLabel = "alpha (LiDAR weight)";
  left.yLabel = "correct [%]";
  left.series = {correct};
  PlotSpec right = left;
  right.title = result.protocol + ": RMSE vs alpha (median)";
  right.yLabel = "RMSE [px]";
  right.series = {rmse};
  io::writeImageAtomically(path, hconcat({linePlot(left), linePlot(right)}));
}

}  // namespace eval
}  // namespace lidar_sgm
