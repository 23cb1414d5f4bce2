// lidar_sgm_eval on a small subset, as a user runs it: the files it writes, and its figures
// against the same frame run through the Densifier (as the tools run it) and scored directly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/ground_truth_cloud.hpp"
#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

/// `environment` goes before the command ("NAME=value ..."), as a shell reads it.
RunResult runTool(const std::string& arguments, const std::string& environment = "") {
  const std::string command = environment + " " + std::string(test::kEvalTool) + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

class EvalCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_eval_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(EvalCli, SmallSyntheticRunWritesEverythingAndItsFiguresAreTheDensifiers) {
  const RunResult r = runTool("-protocols P3 -p3_sets clear64,rain64 -synth_frames 2 -synth_size 310x94 -alpha_step 0.5 "
                              "-threads 2 -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* file : {"results.md", "results.json", "plots/alpha_sweep_p3_clear_64_beams.png",
                           "plots/alpha_sweep_p3_rain_64_beams.png", "pictures/synth_clear_64_3cam_000100.png",
                           "pictures/synth_rain_64_000101.png"}) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / file)) << file;
  }
  std::ifstream jsonFile(dir_ / "results.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  ASSERT_EQ(json.at("protocols").size(), 2u);
  const nlohmann::json& clear = json.at("protocols").at(0);
  EXPECT_EQ(clear.at("protocol"), "P3 clear 64 beams");
  ASSERT_EQ(clear.at("frames").size(), 2u);

  // The same first frame, matched and scored here directly: the tool must report exactly this.
  eval::P3Options options;
  options.frames = 1;
  options.thirdCamera = true;
  options.width = 310;
  options.height = 94;
  const auto frames = eval::loadP3(options);
  ASSERT_EQ(frames.size(), 1u);
  const eval::EvalFrame& f = frames[0];
  // As lidar_sgm_densify runs it: the Densifier on the projected scan.
  Densifier densifier;
  densifier.parameters().numDisparities = f.numDisparities;
  densifier.setComputeCloud(false);
  densifier.setStereoPair(io::grayView(f.left), io::grayView(f.right));
  densifier.runProjected(&f.lidar);
  const eval::DisparityMetrics fused =
      eval::evaluateDisparity(densifier.disparity().view(), f.groundTruth.view(), f.exclude.view());

  const nlohmann::json& frame = clear.at("frames").at(0);
  EXPECT_EQ(frame.at("frame"), f.name);
  bool found = false;
  for (const auto& m : frame.at("methods")) {
    if (m.at("method") != "fused_sgm" || m.at("best_alpha").get<bool>() || m.at("alpha").get<double>() != 0.7) continue;
    found = true;
    EXPECT_DOUBLE_EQ(m.at("correct").get<double>(), fused.correct);
    EXPECT_DOUBLE_EQ(m.at("rmse").get<double>(), fused.rmse);
    EXPECT_DOUBLE_EQ(m.at("density").get<double>(), fused.density);
    // The range the Densifier took from the frame's LiDAR, recorded per frame.
    EXPECT_EQ(m.at("disparity_range").at("num").get<int>(), densifier.usedDisparityRange().numDisparities);
    EXPECT_TRUE(m.at("disparity_range").at("from_lidar").get<bool>());
  }
  EXPECT_TRUE(found) << frame.dump(2);
  EXPECT_EQ(json.at("settings").at("disparity_range"), "lidar");

  std::ifstream md(dir_ / "results.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("## P3 rain 64 beams"), std::string::npos);
  EXPECT_NE(text.str().find("3 cameras + LiDAR (alpha 0.7)"), std::string::npos);
  EXPECT_NE(text.str().find("OpenCV StereoSGBM"), std::string::npos);
  EXPECT_NE(text.str().find("IP-Basic"), std::string::npos);
}

TEST_F(EvalCli, Kitti142PrintsThePapersTablesAndItsFiguresAreTheDensifiers) {
  const std::string root = std::string(test::kSharedDataDir) + "/kitti2015_lidar";
  if (!fs::is_directory(root)) GTEST_SKIP() << "no " << root;
  const RunResult r = runTool("-data " + std::string(test::kSharedDataDir) +
                              " -protocols KITTI142 -kitti142_frames 2 -alpha_step 0.5 -no_pictures -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Both tables on the terminal, ours beside the paper's rows.
  for (const char* text : {"The paper's Table I", "The paper's Table II", "| paper: LiDAR-SGM (alpha 0.7) | 2.06 | 14.47",
                           "| LiDAR-SGM (alpha 0.7) |", "| IP-Basic (morphological) |", "where no input point is",
                           "3D: each method's cloud against the GT's cloud", "| F 40-80 m |"}) {
    EXPECT_NE(r.output.find(text), std::string::npos) << text << " in\n" << r.output;
  }
  std::ifstream jsonFile(dir_ / "results.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  ASSERT_EQ(json.at("protocols").size(), 1u);
  const nlohmann::json& frames = json.at("protocols").at(0).at("frames");
  ASSERT_EQ(frames.size(), 2u);

  // The first frame, loaded and matched here as the tools run it, scored directly.
  const std::vector<eval::EvalFrame> loaded = eval::loadKitti142(test::kSharedDataDir, 1);
  ASSERT_EQ(loaded.size(), 1u);
  const eval::EvalFrame& f = loaded[0];
  EXPECT_TRUE(f.exclude.empty());  // every GT pixel scored, as the paper
  ASSERT_FALSE(f.objectMap.empty());
  Densifier densifier;
  densifier.setComputeCloud(false);
  densifier.setStereoPair(io::grayView(f.left), io::grayView(f.right));
  densifier.runProjected(&f.lidar);
  const eval::DisparityMetrics all = eval::evaluateDisparity(densifier.disparity().view(), f.groundTruth.view());
  const eval::DisparityMetrics uncovered =
      eval::evaluateDisparity(densifier.disparity().view(), f.groundTruth.view(), f.inputPixels.view());
  const eval::ObjectSplitMetrics split =
      eval::evaluateObjectSplit(densifier.disparity().view(), f.groundTruth.view(), f.objectMap.view());
  EXPECT_GT(split.foregroundPixels, 0);
  const nlohmann::json& frame = frames.at(0);
  EXPECT_EQ(frame.at("frame"), f.name);
  bool found = false;
  for (const auto& m : frame.at("methods")) {
    if (m.at("method") != "fused_sgm" || m.at("best_alpha").get<bool>() || m.at("alpha").get<double>() != 0.7) continue;
    found = true;
    EXPECT_DOUBLE_EQ(m.at("correct").get<double>(), all.correct);
    EXPECT_DOUBLE_EQ(m.at("uncovered").at("correct").get<double>(), uncovered.correct);
    EXPECT_DOUBLE_EQ(m.at("object_split").at("foreground").get<double>(), split.foreground);
    EXPECT_DOUBLE_EQ(m.at("object_split").at("total").get<double>(), split.total);
    EXPECT_DOUBLE_EQ(m.at("object_split").at("density").get<double>(), split.density);
    // The cloud against the GT's cloud in 3D, as scored here directly.
    const std::optional<eval::CloudDistanceScore> cloud = eval::GroundTruthCloud(f).score(densifier.disparity().view());
    ASSERT_TRUE(cloud.has_value());
    const nlohmann::json& overall = m.at("cloud_3d").at("overall");
    EXPECT_EQ(overall.at("points").get<long>(), cloud->overall.points);
    EXPECT_EQ(overall.at("reference_points").get<long>(), cloud->overall.referencePoints);
    for (std::size_t t = 0; t < cloud->overall.scores.size(); ++t) {
      EXPECT_DOUBLE_EQ(overall.at("taus").at(t).at("f_score").get<double>(), cloud->overall.scores[t].fScore);
    }
    EXPECT_EQ(m.at("cloud_3d").at("bands").size(), 4u);
  }
  EXPECT_TRUE(found) << frame.dump(2);
}

TEST_F(EvalCli, HalfScaleRunReportsTheDensifiersFiguresAndItsSettings) {
  const RunResult r = runTool("-protocols P3 -p3_sets rain64 -synth_frames 1 -synth_size 310x94 -alpha_step 1 "
                              "-scale 0.5 -threads 2 -no_pictures -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream jsonFile(dir_ / "results.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  EXPECT_EQ(json.at("settings").at("scale").get<double>(), 0.5);
  EXPECT_EQ(json.at("settings").at("threads").get<int>(), 2);

  eval::P3Options options;
  options.frames = 1;
  options.rain = true;
  options.width = 310;
  options.height = 94;
  const auto frames = eval::loadP3(options);
  ASSERT_EQ(frames.size(), 1u);
  const eval::EvalFrame& f = frames[0];
  Densifier densifier;
  densifier.parameters().scale = 0.5f;
  densifier.parameters().numDisparities = eval::numDisparitiesAt(f.numDisparities, 0.5f);
  densifier.setComputeCloud(false);
  densifier.setStereoPair(io::grayView(f.left), io::grayView(f.right));
  densifier.runProjected(&f.lidar);
  const eval::DisparityMetrics fused =
      eval::evaluateDisparity(densifier.disparity().view(), f.groundTruth.view(), f.exclude.view());
  bool found = false;
  for (const auto& m : json.at("protocols").at(0).at("frames").at(0).at("methods")) {
    if (m.at("method") != "fused_sgm" || m.at("best_alpha").get<bool>() || m.at("alpha").get<double>() != 0.7) continue;
    found = true;
    EXPECT_DOUBLE_EQ(m.at("correct").get<double>(), fused.correct);
    EXPECT_DOUBLE_EQ(m.at("rmse").get<double>(), fused.rmse);
  }
  EXPECT_TRUE(found) << json.dump(2);
  std::ifstream md(dir_ / "results.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("matched at scale 0.5"), std::string::npos) << text.str();
}

TEST_F(EvalCli, AdaptiveAlphaRunReportsTheDensifiersFiguresAndItsMode) {
  const RunResult r = runTool("-protocols P3 -p3_sets clear128 -synth_frames 1 -synth_size 310x94 -alpha_step 1 "
                              "-alpha_mode adaptive -threads 2 -no_pictures -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream jsonFile(dir_ / "results.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  EXPECT_EQ(json.at("settings").at("alpha_mode").get<std::string>(), "adaptive");

  eval::P3Options options;
  options.frames = 1;
  options.beams = 128;
  options.width = 310;
  options.height = 94;
  const auto frames = eval::loadP3(options);
  ASSERT_EQ(frames.size(), 1u);
  const eval::EvalFrame& f = frames[0];
  Densifier densifier;
  densifier.parameters().alphaMode = AlphaMode::Adaptive;
  densifier.parameters().numDisparities = f.numDisparities;
  densifier.setComputeCloud(false);
  densifier.setStereoPair(io::grayView(f.left), io::grayView(f.right));
  densifier.runProjected(&f.lidar);
  const eval::DisparityMetrics fused =
      eval::evaluateDisparity(densifier.disparity().view(), f.groundTruth.view(), f.exclude.view());
  bool found = false;
  for (const auto& m : json.at("protocols").at(0).at("frames").at(0).at("methods")) {
    if (m.at("method") != "fused_sgm" || m.at("best_alpha").get<bool>() || m.at("alpha").get<double>() != 0.7) continue;
    found = true;
    EXPECT_DOUBLE_EQ(m.at("correct").get<double>(), fused.correct);
    EXPECT_DOUBLE_EQ(m.at("rmse").get<double>(), fused.rmse);
  }
  EXPECT_TRUE(found) << json.dump(2);
  std::ifstream md(dir_ / "results.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("alpha mode adaptive"), std::string::npos) << text.str();
}

TEST_F(EvalCli, TheDataRootIsTheOptionElseTheEnvironmentElseBesideTheWorkingDirectory) {
  // An empty folder holds no P1 frame: the error names the root the tool looked in.
  const fs::path empty = dir_ / "empty_data";
  fs::create_directories(empty);
  const RunResult fromEnvironment = runTool("-protocols P1 -out " + (dir_ / "out").string(),
                                            "LIDAR_SGM_DATA=" + empty.string());
  EXPECT_NE(fromEnvironment.exitCode, 0);
  EXPECT_NE(fromEnvironment.output.find("under '" + empty.string() + "'"), std::string::npos) << fromEnvironment.output;

  const fs::path other = dir_ / "other_data";
  fs::create_directories(other);
  const RunResult fromOption = runTool("-protocols P1 -data " + other.string() + " -out " + (dir_ / "out").string(),
                                       "LIDAR_SGM_DATA=" + empty.string());
  EXPECT_NE(fromOption.output.find("under '" + other.string() + "'"), std::string::npos) << fromOption.output;

  const RunResult byDefault = runTool("-protocols P1 -out " + (dir_ / "out").string(), "cd " + dir_.string() +
                                      " && LIDAR_SGM_DATA=");
  EXPECT_NE(byDefault.output.find("under '../shared/data'"), std::string::npos) << byDefault.output;
}

TEST_F(EvalCli, NumDisparitiesFixesTheRangeOfEveryLidarSgmMethod) {
  const RunResult r = runTool("-protocols P3 -p3_sets rain64 -synth_frames 1 -synth_size 310x94 -alpha_step 1 "
                              "-num_disparities 64 -threads 2 -no_pictures -out " + dir_.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("disparity range [0, 64) (fixed)"), std::string::npos) << r.output;
  std::ifstream jsonFile(dir_ / "results.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  EXPECT_EQ(json.at("settings").at("disparity_range"), "fixed");
  int matchers = 0;
  for (const auto& m : json.at("protocols").at(0).at("frames").at(0).at("methods")) {
    const std::string id = m.at("method");
    if (id == "ip_basic" || id == "opencv_sgbm") continue;  // IP-Basic searches nothing; SGBM the frame's range
    ++matchers;
    EXPECT_EQ(m.at("disparity_range").at("num").get<int>(), 64) << id;
    EXPECT_FALSE(m.at("disparity_range").at("from_lidar").get<bool>()) << id;
  }
  EXPECT_GE(matchers, 3);  // stereo-only, LiDAR-only, fused
}

TEST_F(EvalCli, BadOptionsFailWithAMessage) {
  for (const auto& [args, message] : {std::pair<std::string, std::string>{"-alpha_step 0", "-alpha_step"},
                                      {"-threads -1", "threads = -1"},
                                      {"-scale 0.7", "scale = 0.7"},
                                      {"-backend gpu", "option -backend"},
                                      {"-synth_size 12", "-synth_size"},
                                      {"-bogus", "unknown option"},
                                      {"-disparity_range gt", "option -disparity_range: 'gt'"},
                                      {"-min_disparity 4", "option -min_disparity"}}) {
    const RunResult r = runTool(args + " -protocols P3 -out " + dir_.string());
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace lidar_sgm
