#include "bench_timing.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace bench {

const std::vector<StageColumn>& stageColumns() {
  static const std::vector<StageColumn> columns = {
      {"census", &StageTimings::census},
      {"censusCost", &StageTimings::censusCost},
      {"lidarCost", &StageTimings::lidarCost},
      {"fuseCosts", &StageTimings::fuseCosts},
      {"aggregatePaths", &StageTimings::aggregatePaths},
      {"selectDisparity", &StageTimings::selectDisparity},
      {"leftRightCheck", &StageTimings::leftRightCheck},
      {"medianFilter", &StageTimings::medianFilter},
      {"confidence", &StageTimings::confidence},
  };
  return columns;
}

double median(std::vector<double> values) {
  if (values.empty()) throw std::logic_error("median of no values");
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

Measurement measureFrames(FrameRunner& runner, MatchMode mode, int runs, int warmups) {
  std::vector<double> frameMs, rescaleMs, transfers, kernel;
  std::vector<std::vector<double>> stageMs(stageColumns().size());
  for (int i = 0; i < warmups + runs; ++i) {
    const double ms = wallClockMs([&] { runner.run(); });
    if (runner.lastMode() != mode) {
      throw std::logic_error("the matcher ran " + toString(runner.lastMode()) + " where the bench asked for " +
                             toString(mode));
    }
    if (i < warmups) continue;
    frameMs.push_back(ms);
    rescaleMs.push_back(runner.rescaleMs());
    transfers.push_back(transfersMs(runner.stages()));
    kernel.push_back(runner.stages().total() - transfers.back());
    for (std::size_t s = 0; s < stageColumns().size(); ++s) {
      stageMs[s].push_back(runner.stages().*stageColumns()[s].member);
    }
  }
  Measurement m;
  m.frameMs = median(frameMs);
  m.rescaleMs = median(rescaleMs);
  m.transfersMs = median(transfers);
  m.kernelMs = median(kernel);
  for (std::size_t s = 0; s < stageColumns().size(); ++s) m.stages.*stageColumns()[s].member = median(stageMs[s]);
  return m;
}

}  // namespace bench
}  // namespace lidar_sgm
