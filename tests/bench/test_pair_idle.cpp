// The bench's pairing with OpenCV's SGBM: each frame of a pair, ours and OpenCV's, starts after the
// idle gap, so that neither runs beside the other's worker threads still spinning after their last
// parallel region (bench_opencv_sgbm.hpp). The gap is what makes the paired ratio fair: back to
// back, libgomp's spinning workers took a core from OpenCV's frame (BENCHMARK.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "bench_opencv_sgbm.hpp"

namespace lidar_sgm {
namespace bench {
namespace {

using Clock = std::chrono::steady_clock;

Frame smallPair() {
  Frame frame;
  frame.left.resize(96, 32);
  frame.right.resize(96, 32);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 96; ++x) {
      frame.left(x, y) = static_cast<std::uint8_t>((x * 37 + y * 11) % 251);
      frame.right(x, y) = static_cast<std::uint8_t>(((x + 4) * 37 + y * 11) % 251);
    }
  }
  return frame;
}

// Between the end of one of our frames and the start of the next lie OpenCV's frame and two gaps.
double shortestPauseBetweenOurFramesMs(int idleMs) {
  SgbmSettings settings;
  settings.numDisparities = 16;
  std::vector<Clock::time_point> starts, ends;
  const PairedTiming t = pairWithOpenCvSgbm(
      smallPair(), settings, 1,
      [&] {
        starts.push_back(Clock::now());
        ends.push_back(Clock::now());
      },
      3, 1, idleMs);
  EXPECT_GT(t.sgbmMs, 0.0);
  EXPECT_EQ(starts.size(), 4u);  // the warm-up pair and three timed ones
  double shortest = 1e9;
  for (std::size_t i = 1; i < starts.size(); ++i) {
    shortest = std::min(shortest, std::chrono::duration<double, std::milli>(starts[i] - ends[i - 1]).count());
  }
  return shortest;
}

TEST(PairWithOpenCvSgbm, EachFrameOfAPairStartsAfterTheIdleGap) {
  // Sleeping is never shorter than asked: the bound holds on any machine, however slow.
  EXPECT_GE(shortestPauseBetweenOurFramesMs(40), 2 * 40.0);
}

}  // namespace
}  // namespace bench
}  // namespace lidar_sgm
