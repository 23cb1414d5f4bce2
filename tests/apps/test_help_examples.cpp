// Every tool's --help as a user reads it: options under headings, 2-4 examples last, every file it
// names present in the repository, and every example a command that works: run here on the
// repository's sample, on frames the synth tool's own examples render, and on a KITTI raw layout
// made from the sample (the same frame, in raw's calibration files). Examples that need the
// third-party KITTI data (their description names ../shared/data) are only parsed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult runShell(const std::string& command) {
  return test::runCommand(command + " 2>&1");
}

struct Example {
  std::string what;
  std::string command;
};

struct ToolHelp {
  std::string name;
  std::string path;
  std::string help;
  std::vector<std::string> headings;  ///< "Inputs", ... in order
  std::vector<Example> examples;
};

/// The built tools, in the order their examples build on each other (synth renders what batch reads).
std::vector<ToolHelp> toolHelps() {
  const std::vector<std::pair<std::string, std::string>> tools{
      {"lidar_sgm_synth", test::kSynthTool},       {"lidar_sgm_densify", test::kDensifyTool},
      {"lidar_sgm_disparity", test::kDisparityTool}, {"lidar_sgm_batch", test::kBatchTool},
      {"lidar_sgm_eval", test::kEvalTool}};
  std::vector<ToolHelp> helps;
  for (const auto& [name, path] : tools) {
    if (path.empty()) continue;
    ToolHelp tool{name, path, runShell(path + " --help").output, {}, {}};
    std::istringstream lines(tool.help);
    std::string line;
    std::string what;
    bool inExamples = false;
    while (std::getline(lines, line)) {
      if (!line.empty() && line[0] != ' ' && line.back() == ':') tool.headings.push_back(line.substr(0, line.size() - 1));
      if (line.rfind("Examples", 0) == 0) inExamples = true;
      if (!inExamples) continue;
      if (line.rfind("    ", 0) == 0) {
        tool.examples.push_back({what, line.substr(4)});
      } else if (line.rfind("  ", 0) == 0) {
        what = line.substr(2);
      }
    }
    helps.push_back(tool);
  }
  return helps;
}

TEST(HelpLayout, OptionsUnderHeadingsAndExamplesLast) {
  const std::vector<ToolHelp> tools = toolHelps();
  if (tools.empty()) GTEST_SKIP() << "no tool is built";
  for (const ToolHelp& tool : tools) {
    SCOPED_TRACE(tool.name);
    ASSERT_FALSE(tool.headings.empty()) << tool.help;
    if (tool.name != "lidar_sgm_synth") {  // the synth tool reads nothing
      EXPECT_EQ(tool.headings.front(), "Inputs") << tool.help;
    }
    EXPECT_EQ(tool.headings.back().rfind("Examples", 0), 0u) << tool.help;
    for (const char* heading : {"Outputs", "Help"}) {
      EXPECT_NE(std::find(tool.headings.begin(), tool.headings.end(), heading), tool.headings.end()) << heading;
    }
    if (tool.name != "lidar_sgm_synth") {  // the synth tool runs no matcher
      for (const char* heading : {"Method", "Speed", "Filters"}) {
        EXPECT_NE(std::find(tool.headings.begin(), tool.headings.end(), heading), tool.headings.end()) << heading;
      }
    }
    EXPECT_GE(tool.examples.size(), 2u);
    EXPECT_LE(tool.examples.size(), 4u);
    for (const Example& example : tool.examples) {
      EXPECT_EQ(example.command.rfind(tool.name + " ", 0), 0u) << example.command;
      EXPECT_FALSE(example.what.empty()) << example.command;
    }
  }
}

TEST(HelpLayout, EveryFileTheHelpNamesExists) {
  const std::regex document(R"(([A-Za-z0-9_./-]+)\.md\b)");
  for (const ToolHelp& tool : toolHelps()) {
    SCOPED_TRACE(tool.name);
    for (std::sregex_iterator it(tool.help.begin(), tool.help.end(), document), end; it != end; ++it) {
      const std::string file = (*it)[1].str() + ".md";
      const std::string first = file.substr(0, file.find('/'));
      // A placeholder's output (DIR/confidence_fit.md) is no file of the repository.
      if (file.find('/') != std::string::npos && std::all_of(first.begin(), first.end(), ::isupper)) continue;
      EXPECT_TRUE(fs::is_regular_file(fs::path(test::kSourceDir) / file)) << file << " is named but not in the repository";
    }
  }
}

/// KITTI object calibration "KEY: values" lines.
std::map<std::string, std::string> objectCalibration(const fs::path& file) {
  std::map<std::string, std::string> keys;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos) keys[line.substr(0, colon)] = line.substr(colon + 1);
  }
  return keys;
}

/// The sample frame as a KITTI raw date folder: 2011_09_26/{calib_cam_to_cam,calib_velo_to_cam}.txt
/// and the drive 2011_09_26_drive_0005_sync with frame 0000000000.
void makeRawLayout(const fs::path& root) {
  const fs::path sample(test::kSampleDir);
  const fs::path date = root / "2011_09_26";
  const fs::path drive = date / "2011_09_26_drive_0005_sync";
  std::map<std::string, std::string> object = objectCalibration(sample / "calib" / "000000.txt");
  std::istringstream tr(object["Tr_velo_to_cam"]);
  std::vector<std::string> v;
  for (std::string value; tr >> value;) v.push_back(value);
  ASSERT_EQ(v.size(), 12u);
  fs::create_directories(date);
  std::ofstream(date / "calib_cam_to_cam.txt")
      << "calib_time: 09-Jan-2012 13:57:47\nS_rect_02: 1242 375\nP_rect_02:" << object["P2"]
      << "\nP_rect_03:" << object["P3"] << "\nR_rect_00:" << object["R0_rect"] << "\n";
  std::ofstream(date / "calib_velo_to_cam.txt")
      << "calib_time: 15-Mar-2012 11:37:16\nR: " << v[0] << " " << v[1] << " " << v[2] << " " << v[4] << " " << v[5]
      << " " << v[6] << " " << v[8] << " " << v[9] << " " << v[10] << "\nT: " << v[3] << " " << v[7] << " " << v[11]
      << "\n";
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"velodyne/000000.bin", "velodyne_points/data/0000000000.bin"},
           {"image_2/000000.png", "image_02/data/0000000000.png"},
           {"image_3/000000.png", "image_03/data/0000000000.png"}}) {
    fs::create_directories((drive / to).parent_path());
    fs::copy_file(sample / from, drive / to);
  }
}

TEST(HelpExamples, EveryExampleRuns) {
  const std::vector<ToolHelp> tools = toolHelps();
  bool densifyBuilt = false;
  for (const ToolHelp& tool : tools) densifyBuilt = densifyBuilt || tool.name == "lidar_sgm_densify";
  if (!densifyBuilt) GTEST_SKIP() << "lidar_sgm_densify is not built";
  const fs::path work = fs::temp_directory_path() / ("lidar_sgm_help_examples_" + std::to_string(::getpid()));
  fs::remove_all(work);
  fs::create_directories(work);
  // The examples name data/sample/ as from the repository's root.
  fs::create_directory_symlink(fs::path(test::kSourceDir) / "data", work / "data");
  makeRawLayout(work);
  int ran = 0;
  for (const ToolHelp& tool : tools) {
    for (const Example& example : tool.examples) {
      if (example.what.find("../shared/data") != std::string::npos) continue;  // third-party KITTI data
      const std::string command = "cd '" + work.string() + "' && '" + tool.path + "'" +
                                  example.command.substr(tool.name.size());
      const RunResult result = runShell(command);
      EXPECT_EQ(result.exitCode, 0) << example.command << "\n" << result.output;
      if (tool.name == "lidar_sgm_densify") ++ran;
    }
  }
  EXPECT_GE(ran, 3);  // every densify example: the sample, LiDAR-only half scale, KITTI raw
  // What they said they would write.
  for (const char* output : {"dense.pcd", "disparity.png", "preview.png", "lidar_only.ply", "raw.pcd"}) {
    EXPECT_TRUE(fs::is_regular_file(work / output)) << output;
  }
  std::error_code ec;
  fs::remove_all(work, ec);
}

}  // namespace
}  // namespace lidar_sgm
