#pragma once
// Timing: the median of many frames after warm-up ones, per frame and per stage.

#include <chrono>
#include <type_traits>
#include <utility>
#include <vector>

#include "bench_frame.hpp"
#include "bench_runner.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace bench {

/// Medians over the timed runs of one configuration (each figure its own median, so the stages
/// need not add up to the frame exactly).
struct Measurement {
  double frameMs = 0;   ///< wall clock around one frame (FrameRunner::run): what a caller waits for
  StageTimings stages;  ///< Matcher::lastTimings()
  double rescaleMs = 0; ///< Matcher::lastRescaleMs(): half scale only, outside the stages
  double transfersMs = 0;  ///< host<->device copies (transfersMs() below); 0 on CPU backends
  double kernelMs = 0;     ///< stages without the copies: StageTimings::total() - transfers
};

/// The host<->device copy time of a frame [ms] (StageTimings::transfers; 0 on CPU backends).
inline double transfersMs(const StageTimings& timings) { return timings.transfers; }

/// A stage column of the table, in the order the stages run.
struct StageColumn {
  const char* name;
  double StageTimings::*member;
};
const std::vector<StageColumn>& stageColumns();

/// The median; the mean of the two middle values for an even count. `values` must not be empty.
double median(std::vector<double> values);

/// Milliseconds `fn` takes, by the steady clock.
template <typename Fn>
double wallClockMs(Fn&& fn) {
  const auto start = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Median wall-clock milliseconds of `runs` calls of `fn` after `warmups` untimed ones (they
/// fault in the buffers and warm the caches, as in a frame sequence).
template <typename Fn>
double medianMs(Fn&& fn, int runs, int warmups) {
  for (int i = 0; i < warmups; ++i) fn();
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) ms.push_back(wallClockMs(fn));
  return median(ms);
}

/// Runs `runner`'s frame `warmups` + `runs` times and returns the medians of the timed runs.
/// After every frame it checks that the matcher really ran in `mode` (lastMode()) and throws
/// std::logic_error if not, so a row of the table cannot claim a mode it did not time.
Measurement measureFrames(FrameRunner& runner, MatchMode mode, int runs, int warmups);

}  // namespace bench
}  // namespace lidar_sgm
