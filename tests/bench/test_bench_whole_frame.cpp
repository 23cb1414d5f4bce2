// lidar_sgm_bench -kitti_frame: the whole frame as the tools run it, paired with OpenCV's SGBM.
// One frame of each whole-frame configuration; the cloud it times is the one lidar_sgm_densify
// writes for the same frame (same point count), so the bench cannot drift from the tools.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult run(const std::string& command) {
  return test::runCommand(command + " 2>&1");
}

/// The key=value pairs of the "result config=<config> ..." line; empty when there is none.
std::map<std::string, std::string> resultLine(const std::string& output, const std::string& config) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("result config=" + config + " ", 0) != 0) continue;
    std::map<std::string, std::string> values;
    std::istringstream words(line.substr(7));
    std::string word;
    while (words >> word) {
      const auto eq = word.find('=');
      if (eq != std::string::npos) values[word.substr(0, eq)] = word.substr(eq + 1);
    }
    return values;
  }
  return {};
}

const fs::path kKitti = fs::path(test::kSharedDataDir) / "kitti2015_lidar";
const char* kFrame = "000007_10";

class BenchWholeFrame : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!*test::kBenchTool) GTEST_SKIP() << "lidar_sgm_bench is not built";
    if (!fs::is_directory(kKitti)) GTEST_SKIP() << kKitti << " is absent";
  }
  std::string bench() const {
    return std::string(test::kBenchTool) + " -data " + test::kSharedDataDir + " -threads 2";
  }
};

TEST_F(BenchWholeFrame, TimesTheCloudTheDensifyToolWrites) {
  const RunResult r = run(bench() + " -kitti_frame 000007 -runs 1 -warmups 0");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("| densifier |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| densifier_half |"), std::string::npos) << r.output;
  const auto full = resultLine(r.output, "densifier");
  const auto half = resultLine(r.output, "densifier_half");
  ASSERT_FALSE(full.empty()) << r.output;
  ASSERT_FALSE(half.empty()) << r.output;
  for (const auto* values : {&full, &half}) {
    for (const char* key : {"frame_ms", "project_ms", "match_ms", "kernel_ms", "filters_ms", "reproject_ms", "sgbm_ms",
                            "ratio", "peak_rss_mib"}) {
      ASSERT_EQ(values->count(key), 1u) << key << "\n" << r.output;
      EXPECT_GT(std::stod(values->at(key)), 0.0) << key << "\n" << r.output;
    }
    // The steps are parts of the frame, the core's stages and the filters parts of the match.
    EXPECT_LE(std::stod(values->at("match_ms")), std::stod(values->at("frame_ms")));
    EXPECT_LE(std::stod(values->at("kernel_ms")) + std::stod(values->at("filters_ms")), std::stod(values->at("match_ms")));
    EXPECT_GT(std::stoi(values->at("disparities")), 0);
  }
  EXPECT_EQ(full.at("scale"), "1");
  EXPECT_EQ(half.at("scale"), "0.5");
  // The half-scale frame against OpenCV's full-scale one, from the two rows' medians.
  const auto across = resultLine(r.output, "densifier_half_vs_full_sgbm");
  ASSERT_FALSE(across.empty()) << r.output;
  EXPECT_EQ(std::stod(across.at("half_frame_ms")), std::stod(half.at("frame_ms")));
  EXPECT_EQ(std::stod(across.at("full_sgbm_ms")), std::stod(full.at("sgbm_ms")));
  EXPECT_NEAR(std::stod(across.at("ratio")), std::stod(half.at("frame_ms")) / std::stod(full.at("sgbm_ms")), 1e-3);

  if (!*test::kDensifyTool) return;
  const fs::path out = fs::temp_directory_path() / ("lidar_sgm_bench_whole_" + std::to_string(::getpid()) + ".pcd");
  const std::string scan = (kKitti / "velodyne" / (std::string(kFrame) + ".bin")).string();
  const RunResult tool = run(std::string(test::kDensifyTool) + " " + scan + " " + out.string() + " -calib " +
                             (kKitti / "calib/calib_cam_to_cam.txt").string() + " -left " +
                             (kKitti / "image_2" / (std::string(kFrame) + ".png")).string() + " -right " +
                             (kKitti / "image_3" / (std::string(kFrame) + ".png")).string());
  ASSERT_EQ(tool.exitCode, 0) << tool.output;
  std::ifstream pcd(out, std::ios::binary);
  std::string line, points;
  while (std::getline(pcd, line) && line.rfind("DATA", 0) != 0) {
    if (line.rfind("POINTS ", 0) == 0) points = line.substr(7);
  }
  fs::remove(out);
  EXPECT_EQ(full.at("points"), points) << "the bench's frame is not the tool's";
}

// The hidden-LiDAR filter's stereo witness is a part of the fused match, and
// -no_hidden_lidar_filter times the frame without it: the witness column is what the filter costs.
TEST_F(BenchWholeFrame, WitnessColumnIsTheHiddenLidarFiltersMatch) {
  const std::string command = bench() + " -kitti_frame 000007 -configs densifier -runs 1 -warmups 0";
  const RunResult with = run(command);
  const RunResult without = run(command + " -no_hidden_lidar_filter");
  ASSERT_EQ(with.exitCode, 0) << with.output;
  ASSERT_EQ(without.exitCode, 0) << without.output;
  const auto on = resultLine(with.output, "densifier");
  const auto off = resultLine(without.output, "densifier");
  ASSERT_EQ(on.count("witness_ms"), 1u) << with.output;
  ASSERT_EQ(off.count("witness_ms"), 1u) << without.output;
  EXPECT_GT(std::stod(on.at("witness_ms")), 0.0) << with.output;
  EXPECT_LE(std::stod(on.at("witness_ms")) + std::stod(on.at("kernel_ms")), std::stod(on.at("match_ms")))
      << with.output;
  EXPECT_EQ(std::stod(off.at("witness_ms")), 0.0) << without.output;
  // Without the filter every projected point reaches the matcher: the clouds differ.
  EXPECT_NE(on.at("points"), off.at("points")) << with.output << without.output;
}

TEST_F(BenchWholeFrame, WholeFrameConfigurationsNeedAFrameAndAMissingFrameIsNamed) {
  const RunResult noFrame = run(std::string(test::kBenchTool) + " -synthetic -configs densifier -runs 1");
  EXPECT_EQ(noFrame.exitCode, 1) << noFrame.output;
  EXPECT_NE(noFrame.output.find("give -kitti_frame ID"), std::string::npos) << noFrame.output;
  const RunResult missing = run(bench() + " -kitti_frame 999999 -runs 1");
  EXPECT_EQ(missing.exitCode, 1) << missing.output;
  EXPECT_NE(missing.output.find("999999_10"), std::string::npos) << missing.output;
}

// The idle gap before each frame of a pair is printed with the table, and a negative one refused.
TEST_F(BenchWholeFrame, PairIdleIsPrintedAndANegativeOneRefused) {
  const RunResult r = run(bench() + " -kitti_frame 000007 -configs densifier -runs 1 -warmups 0 -pair_idle_ms 7");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("each frame after 7 ms idle (-pair_idle_ms)"), std::string::npos) << r.output;
  const RunResult negative = run(bench() + " -kitti_frame 000007 -runs 1 -pair_idle_ms -1");
  EXPECT_EQ(negative.exitCode, 1) << negative.output;
  EXPECT_NE(negative.output.find("-pair_idle_ms must be in [0, 10000]"), std::string::npos) << negative.output;
}

}  // namespace
}  // namespace lidar_sgm
