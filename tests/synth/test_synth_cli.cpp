// lidar_sgm_synth as a user runs it: help, rejected options leave nothing behind, the layout.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "synth/synth_test_helpers.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult runTool(const std::string& arguments) {
  const std::string command = std::string(test::kSynthTool) + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

class SynthCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_synth_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SynthCli, HelpListsEveryOptionWithDefaults) {
  const RunResult r = runTool("-h");
  EXPECT_EQ(r.exitCode, 0);
  for (const char* option : {"-out", "-n", "-seed", "-weather", "-beams", "-third_camera", "-baseline", "-width",
                             "-lidar_in_camera_view", "default: 0.54", "default: 64", "-sequence", "-step",
                             "default: 0.8", "poses.txt", "times.txt", "calib.txt"}) {
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
  }
}

TEST_F(SynthCli, BadValuesAreRejectedAndLeaveNoOutput) {
  const std::string out = " -out " + dir_.string();
  const std::pair<std::string, std::string> cases[] = {
      {"-beams 32" + out, "beams"},          {"-weather snow" + out, "weather"},
      {"-baseline 0" + out, "baseline"},     {"-baseline abc" + out, "baseline"},
      {"-n 0" + out, "-n"},                  {"-seed -1" + out, "-seed"},
      {"-width 8" + out, "image size"},      {"-bogus 1" + out, "bogus"},
      {"-n 1", "-out"},                      {"extra" + out, "extra"},
      {"-sequence 0" + out, "-sequence"},    {"-sequence -4" + out, "-sequence"},
      {"-sequence 3 -n 3" + out, "exclude"}, {"-n 3 -sequence 3" + out, "exclude"},
      {"-step 1" + out, "-step"},            {"-sequence 2 -step 0" + out, "step"},
      {"-sequence 2 -step 6" + out, "step"}, {"-sequence two" + out, "-sequence"},
      {"-sequence 200000" + out, "sequence length"},
  };
  for (const auto& [arguments, message] : cases) {
    const RunResult r = runTool(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find("Error"), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir_)) << arguments;
  }
}

TEST_F(SynthCli, WritesTheKittiLayout) {
  const RunResult r =
      runTool("-n 2 -seed 4 -width 160 -height 64 -third_camera -weather rain -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* folder : {"image_2", "image_3", "image_up", "disp_gt", "depth_gt", "mask", "lidar_disp"}) {
    for (const char* id : {"000000", "000001"}) {
      EXPECT_TRUE(fs::is_regular_file(dir_ / folder / (std::string(id) + ".png"))) << folder << "/" << id;
    }
  }
  const auto binSize = fs::file_size(dir_ / "velodyne" / "000001.bin");
  EXPECT_GT(binSize, 0u);
  EXPECT_EQ(binSize % 16, 0u);
  std::ifstream calib(dir_ / "calib" / "000000.txt");
  std::stringstream text;
  text << calib.rdbuf();
  const auto rows = test::parseCalibration(text.str());
  for (const char* key : {"P0", "P1", "P2", "P3", "R0_rect", "Tr_velo_to_cam", "P_up"}) {
    EXPECT_EQ(rows.count(key), 1u) << key;
  }
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
    files += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(files, 2u * 9u);  // 2 frames x (7 PNG folders + velodyne + calib)
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::vector<double>> numberLines(const fs::path& path) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(fileText(path));
  for (std::string line; std::getline(in, line);) {
    std::istringstream values(line);
    rows.emplace_back();
    for (double v = 0; values >> v;) rows.back().push_back(v);
  }
  return rows;
}

TEST_F(SynthCli, WritesAKittiOdometrySequence) {
  const RunResult r = runTool("-sequence 3 -step 1.5 -seed 2 -width 160 -height 64 -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* id : {"000000", "000001", "000002"}) {
    for (const char* folder : {"image_2", "image_3", "disp_gt", "depth_gt", "mask", "lidar_disp"}) {
      EXPECT_TRUE(fs::is_regular_file(dir_ / folder / (std::string(id) + ".png"))) << folder << "/" << id;
    }
    EXPECT_TRUE(fs::is_regular_file(dir_ / "calib" / (std::string(id) + ".txt"))) << id;
    const auto binSize = fs::file_size(dir_ / "velodyne" / (std::string(id) + ".bin"));
    EXPECT_GT(binSize, 0u);
    EXPECT_EQ(binSize % 16, 0u);
  }
  // poses.txt: frame i's left camera into frame 0's, 1.5 m further along +z (forward) each frame.
  const auto poses = numberLines(dir_ / "poses.txt");
  ASSERT_EQ(poses.size(), 3u);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    ASSERT_EQ(poses[i].size(), 12u) << i;
    const double expected[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1.5 * static_cast<double>(i)};
    for (std::size_t k = 0; k < 12; ++k) EXPECT_NEAR(poses[i][k], expected[k], 1e-12) << i << " " << k;
  }
  const auto times = numberLines(dir_ / "times.txt");
  ASSERT_EQ(times.size(), 3u);
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(times[i].at(0), 0.1 * static_cast<double>(i), 1e-9);
  // calib.txt: the odometry keys only, 12 numbers each; one rig: P0 = P2, P1 = P3; Tr as Tr_velo_to_cam.
  const auto rows = test::parseCalibration(fileText(dir_ / "calib.txt"));
  EXPECT_EQ(rows.size(), 5u);
  for (const char* key : {"P0", "P1", "P2", "P3", "Tr"}) {
    ASSERT_EQ(rows.count(key), 1u) << key;
    EXPECT_EQ(rows.at(key).size(), 12u) << key;
  }
  EXPECT_EQ(rows.at("P0"), rows.at("P2"));
  EXPECT_EQ(rows.at("P1"), rows.at("P3"));
  EXPECT_EQ(rows.at("Tr"), test::parseCalibration(fileText(dir_ / "calib" / "000000.txt")).at("Tr_velo_to_cam"));
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
    files += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(files, 3u * 8u + 3u);  // 3 frames x (6 PNG folders + velodyne + calib), calib/poses/times.txt
}

TEST_F(SynthCli, SequenceIsTheSameBytesEveryRun) {
  const fs::path again = dir_.string() + "_again";
  fs::remove_all(again);
  const std::string options = "-sequence 2 -seed 5 -width 96 -height 40 -out ";
  ASSERT_EQ(runTool(options + dir_.string()).exitCode, 0);
  ASSERT_EQ(runTool(options + again.string()).exitCode, 0);
  for (const char* file : {"poses.txt", "times.txt", "calib.txt", "velodyne/000001.bin", "image_2/000001.png",
                           "image_3/000000.png", "depth_gt/000001.png"}) {
    EXPECT_EQ(fileText(dir_ / file), fileText(again / file)) << file;
  }
  EXPECT_NE(fileText(dir_ / "velodyne/000000.bin"), fileText(dir_ / "velodyne/000001.bin"));
  fs::remove_all(again);
}

}  // namespace
}  // namespace lidar_sgm
