// lidar_sgm_synth as a user runs it: help, rejected options leave nothing behind, the layout.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "synth/synth_test_helpers.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

struct RunResult {
  int exitCode;
  std::string output;  // stdout + stderr
};

RunResult runTool(const std::string& arguments) {
  const std::string command = std::string(LIDAR_SGM_SYNTH_TOOL) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 512> buffer{};
  while (pipe && fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

class SynthCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_synth_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SynthCli, HelpListsEveryOptionWithDefaults) {
  const RunResult r = runTool("-h");
  EXPECT_EQ(r.exitCode, 0);
  for (const char* option : {"-out", "-n", "-seed", "-weather", "-beams", "-third_camera", "-baseline", "-width",
                             "-lidar_in_camera_view", "default: 0.54", "default: 64"}) {
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

}  // namespace
}  // namespace lidar_sgm
