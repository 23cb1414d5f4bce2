// The batch's worker pool: records come back in frame order whatever the workers' speeds, a stop
// leaves a finished prefix, and an escaping exception stops the run and reaches the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "lidar_sgm/sequence/frame_runner.hpp"

namespace lidar_sgm {
namespace sequence {
namespace {

FrameRecord recordOf(std::size_t index) {
  FrameRecord r;
  r.frame = std::to_string(index);
  r.status = "ok";
  return r;
}

TEST(FrameRunner, RecordsComeBackInFrameOrderWhateverTheWorkersSpeed) {
  for (int jobs : {1, 2, 3, 5}) {
    std::vector<std::string> seen;
    std::atomic<int> maxWorker{0};
    const std::size_t finished = runFramesInOrder(
        17, jobs,
        [&](std::size_t index, int worker) {
          // Early frames slowest, so later ones finish first on other workers.
          std::this_thread::sleep_for(std::chrono::milliseconds(index % 4 == 0 ? 12 : 1));
          int m = maxWorker.load();
          while (worker > m && !maxWorker.compare_exchange_weak(m, worker)) {
          }
          return recordOf(index);
        },
        [&](std::size_t index, const FrameRecord& r) {
          EXPECT_EQ(r.frame, std::to_string(index));
          seen.push_back(r.frame);
        },
        [] { return false; });
    EXPECT_EQ(finished, 17u);
    ASSERT_EQ(seen.size(), 17u) << jobs;
    for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], std::to_string(i)) << jobs;
    EXPECT_LT(maxWorker.load(), jobs);
  }
}

TEST(FrameRunner, AStopLeavesAFinishedPrefixAndNoFrameHalfDone) {
  std::atomic<int> started{0};
  std::atomic<int> completed{0};
  std::vector<std::size_t> seen;
  const std::size_t finished = runFramesInOrder(
      100, 3,
      [&](std::size_t index, int) {
        ++started;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        ++completed;
        return recordOf(index);
      },
      [&](std::size_t index, const FrameRecord&) { seen.push_back(index); },
      [&] { return started.load() >= 10; });
  EXPECT_GE(finished, 10u);
  EXPECT_LT(finished, 100u);
  EXPECT_EQ(static_cast<int>(finished), started.load()) << "every frame taken was finished and handed back";
  EXPECT_EQ(completed.load(), started.load());
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], i);
}

TEST(FrameRunner, AnEscapingExceptionStopsTheRunAndReachesTheCaller) {
  std::atomic<int> started{0};
  EXPECT_THROW(runFramesInOrder(
                   50, 2,
                   [&](std::size_t index, int) {
                     ++started;
                     if (index == 5) throw std::runtime_error("disk full");
                     // A frame takes time, as a real one does: without it, the other worker could
                     // finish all 50 before the failing one is scheduled again (seen on 2 loaded cores).
                     std::this_thread::sleep_for(std::chrono::milliseconds(20));
                     return recordOf(index);
                   },
                   [](std::size_t, const FrameRecord&) {}, [] { return false; }),
               std::runtime_error);
  EXPECT_LT(started.load(), 50);
  EXPECT_THROW(runFramesInOrder(3, 0, nullptr, nullptr, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace sequence
}  // namespace lidar_sgm
