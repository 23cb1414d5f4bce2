// Every tool's command line as a user types it: -h, --help and --version answer and do nothing
// else; a bad line exits 1 with a one-line message naming the problem, never an abort.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"
#include "lidar_sgm/version.hpp"

namespace lidar_sgm {
namespace {

using RunResult = test::CommandResult;

RunResult run(const std::string& tool, const std::string& arguments) {
  const std::string command = tool + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

/// A tool, and for each kind of bad line one that reaches the parser (some tools check their
/// files before their numbers) with the message it must print.
struct Tool {
  const char* name;
  const char* path;
  const char* missingValue;  ///< an option given last, without its value
  std::string badNumber;     ///< a line with a non-numeric value
  const char* badNumberMessage;
  std::string wrongPositionals;
  const char* wrongPositionalsMessage;
};

void PrintTo(const Tool& tool, std::ostream* os) { *os << tool.name; }

std::vector<Tool> builtTools() {
  std::vector<Tool> tools;
  if (*test::kDisparityTool) {
    tools.push_back({"lidar_sgm_disparity", test::kDisparityTool, "-alpha", "l.png r.png o.png -paths four",
                     "option -paths: 'four' is not an integer", "l.png", "expected LEFT.png [RIGHT.png] OUT.png, got 1"});
  }
  if (*test::kSynthTool) {
    tools.push_back({"lidar_sgm_synth", test::kSynthTool, "-out", "-out never_written -n two",
                     "option -n: 'two' is not an integer", "stray", "unexpected argument 'stray'"});
  }
  if (*test::kDensifyTool) {
    tools.push_back({"lidar_sgm_densify", test::kDensifyTool, "-calib", "in.bin out.pcd -calib c.txt -alpha high",
                     "option -alpha: 'high' is not a finite number", "in.bin", "expected INPUT and OUTPUT, got 1"});
  }
  if (*test::kBatchTool) {
    tools.push_back({"lidar_sgm_batch", test::kBatchTool, "-output_dir", "-list l.txt -output_dir o -alpha high",
                     "option -alpha: 'high' is not a finite number", "stray",
                     "unexpected argument 'stray' (the frames come from -input_dir or -list; see -h)"});
  }
  if (*test::kEvalTool) {
    tools.push_back({"lidar_sgm_eval", test::kEvalTool, "-out", "-synth_frames ten",
                     "option -synth_frames: 'ten' is not an integer", "stray", "unexpected argument 'stray'"});
  }
  if (*test::kBenchTool) {
    tools.push_back({"lidar_sgm_bench", test::kBenchTool, "-runs", "-runs abc", "option -runs: 'abc' is not an integer",
                     "stray", "unexpected argument 'stray'"});
  }
  if (*test::kOcclusionStudyTool) {
    tools.push_back({"occlusion_filter_study", test::kOcclusionStudyTool, "-seeds", "-seeds many",
                     "option -seeds: 'many' is not an integer", "stray", "unexpected argument 'stray'"});
  }
  return tools;
}

class ToolOptions : public ::testing::TestWithParam<Tool> {};

TEST_P(ToolOptions, HelpInEverySpellingPrintsTheOptionsAndDoesNothingElse) {
  for (const char* help : {"-h", "--help", "-help"}) {
    const RunResult r = run(GetParam().path, help);
    EXPECT_EQ(r.exitCode, 0) << help << ":\n" << r.output;
    EXPECT_NE(r.output.find("-h, --help"), std::string::npos) << help << ":\n" << r.output;
    EXPECT_NE(r.output.find("--version"), std::string::npos) << help << ":\n" << r.output;
    // Every tool's work prints "[done, ...]" lines (loading, matching, timing); help prints none.
    EXPECT_EQ(r.output.find("[done"), std::string::npos) << help << " did some work:\n" << r.output;
  }
}

TEST_P(ToolOptions, HelpWinsOverTheRestOfTheLine) {
  // The bench would otherwise time frames for seconds, the evaluation run for minutes.
  const RunResult r = run(GetParam().path, "-runs 1 -out never_written -h");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("[done"), std::string::npos) << r.output;
}

/// The one-shot tools name their allocator in a second line of --version (one_shot_allocator.hpp).
bool isOneShotTool(const std::string& name) { return name == "lidar_sgm_densify" || name == "lidar_sgm_disparity"; }

TEST_P(ToolOptions, VersionPrintsTheToolAndTheLibraryVersion) {
  for (const char* version : {"--version", "-version"}) {
    const RunResult r = run(GetParam().path, version);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const std::string first = std::string(GetParam().name) + " " + LIDAR_SGM_VERSION_STRING + "\n";
    if (isOneShotTool(GetParam().name)) {
      EXPECT_EQ(r.output.substr(0, first.size()), first);
      EXPECT_EQ(r.output.find('\n', first.size()), r.output.size() - 1) << "one line more:\n" << r.output;
      EXPECT_EQ(r.output.compare(first.size(), 11, "allocator: "), 0) << r.output;
    } else {
      EXPECT_EQ(r.output, first);
    }
  }
}

// A one-shot process writes every buffer for the first time: on huge pages, through jemalloc,
// where the build found it. The line is read from jemalloc itself at run time (its version, its
// THP option, and whether malloc's blocks are counted by it), so it fails if the tool is linked
// without jemalloc, if jemalloc does not read the tool's options, or if malloc is not jemalloc's.
TEST(OneShotTools, AllocateThroughJemallocOnHugePages) {
#ifndef LIDAR_SGM_TOOLS_WITH_JEMALLOC
  GTEST_SKIP() << "the build found no jemalloc (Debian: libjemalloc-dev)";
#else
  for (const Tool& tool : builtTools()) {
    if (!isOneShotTool(tool.name)) continue;
    const RunResult r = run(tool.path, "--version");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("\nallocator: jemalloc 5."), std::string::npos) << tool.name << ":\n" << r.output;
    EXPECT_NE(r.output.find(", transparent huge pages: always\n"), std::string::npos) << tool.name << ":\n" << r.output;
  }
#endif
}

TEST_P(ToolOptions, UnknownOptionExitsOneNamingIt) {
  for (const char* option : {"-no_such_option", "--no_such_option"}) {
    const RunResult r = run(GetParam().path, option);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(std::string("unknown option ") + option), std::string::npos) << r.output;
  }
}

TEST_P(ToolOptions, MissingValueExitsOneNamingTheOption) {
  const std::string option = GetParam().missingValue;
  for (const std::string& spelling : {option, "-" + option}) {  // -name and --name
    const RunResult r = run(GetParam().path, spelling);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("option " + option + " needs a value"), std::string::npos) << r.output;
  }
}

TEST_P(ToolOptions, NonNumericValueExitsOneNamingTheOption) {
  const RunResult r = run(GetParam().path, GetParam().badNumber);
  EXPECT_EQ(r.exitCode, 1) << r.output;  // 134 was std::stoi's uncaught exception
  EXPECT_NE(r.output.find(GetParam().badNumberMessage), std::string::npos) << r.output;
}

TEST_P(ToolOptions, WrongPositionalsExitOne) {
  const RunResult r = run(GetParam().path, GetParam().wrongPositionals);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(GetParam().wrongPositionalsMessage), std::string::npos) << r.output;
}

// The tools that run the Densifier take its output-filter options, list them in -h and refuse an
// out-of-range value naming it (before reading any file).
TEST_P(ToolOptions, OutputFilterOptionsAreListedAndChecked) {
  const std::string name = GetParam().name;
  if (name != "lidar_sgm_disparity" && name != "lidar_sgm_densify" && name != "lidar_sgm_batch") {
    GTEST_SKIP() << name << " runs no Densifier";
  }
  const RunResult help = run(GetParam().path, "-h");
  for (const char* option : {"-no_sky_filter", "-sky_texture", "-no_outlier_filter", "-outlier_min_neighbours"}) {
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  }
  const std::string line = name == "lidar_sgm_densify" ? "in.bin out.pcd -calib c.txt -outlier_min_neighbours 30"
                           : name == "lidar_sgm_batch" ? "-list l.txt -output_dir o -outlier_min_neighbours 30"
                                                       : "l.png r.png o.png -outlier_min_neighbours 30";
  const RunResult r = run(GetParam().path, line);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("minNeighbours must be in [0, 24]"), std::string::npos) << r.output;
}

INSTANTIATE_TEST_SUITE_P(EveryTool, ToolOptions, ::testing::ValuesIn(builtTools()),
                         [](const ::testing::TestParamInfo<Tool>& tool) { return std::string(tool.param.name); });

TEST(EvalToolOptions, WithoutArgumentsPrintsThePlanAndRunsNothing) {
  if (!*test::kEvalTool) GTEST_SKIP() << "lidar_sgm_eval is not built";
  const RunResult r = run(test::kEvalTool, "");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  for (const char* part : {"protocols: P1, P2, KITTI142, P3", "methods:", "outputs:", "-out DIR is required",
                           "disparity range from each frame's LiDAR (without LiDAR: the frame's)"}) {
    EXPECT_NE(r.output.find(part), std::string::npos) << part << " in:\n" << r.output;
  }
  EXPECT_EQ(r.output.find("Loading"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lidar_sgm
