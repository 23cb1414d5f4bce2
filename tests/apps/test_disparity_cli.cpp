// The lidar_sgm_disparity tool as a user runs it: exit codes, messages, files left behind.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/synthetic_stereo.hpp"
#include "common/test_data.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult runTool(const std::string& arguments) {
  const std::string command = std::string(test::kDisparityTool) + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

class DisparityCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const test::SyntheticStereo s = test::makeStereo(97, 61, [](double x, double) { return 6.0 + 0.05 * x; });
    write("left.png", cv::Mat(61, 97, CV_8UC1, const_cast<std::uint8_t*>(s.left.data())).clone());
    write("right.png", cv::Mat(61, 97, CV_8UC1, const_cast<std::uint8_t*>(s.right.data())).clone());
    cv::Mat sparse(61, 97, CV_16UC1, cv::Scalar(0));
    for (int y = 0; y < 61; y += 4) {
      for (int x = 0; x < 97; x += 3) sparse.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(s.disparity(x, y) * 256);
    }
    write("sparse.png", sparse);
    write("small.png", cv::Mat(60, 97, CV_8UC1, cv::Scalar(3)));
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const cv::Mat& image) { ASSERT_TRUE(cv::imwrite(p(name), image)); }
  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  // A failing call must exit non-zero, say `message`, and leave no new file behind.
  void expectFailure(const std::string& arguments, const std::string& message) {
    const std::size_t before = fileCount();
    const RunResult r = runTool(arguments);
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << "expected '" << message << "' in:\n" << r.output;
    EXPECT_EQ(fileCount(), before) << "a failed run left a file behind";
    EXPECT_FALSE(fs::exists(p("out.png")));
  }
  fs::path dir_;
};

TEST_F(DisparityCli, HelpListsEveryOptionWithItsDefault) {
  const RunResult r = runTool("-h");
  EXPECT_EQ(r.exitCode, 0);
  for (const char* option : {"-lidar ", "-lidar_depth", "-fb", "-alpha", "-sigma", "-num_disparities",
                             "-min_disparity", "-paths", "-p1", "-p2", "-uniqueness", "-no_lr_check", "-median",
                             "-backend", "-color", "(default: 0.7)", "(default: 128)", "(default: 100)", "-scale 1|0.5",
                             "-threads N", "0 = all hardware threads", "cpu_ref, cpu",
                             "-disparity_range lidar|fixed", "(default: lidar"}) {
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
  }
}

TEST_F(DisparityCli, FusedRunWritesKittiDisparityAndPicture) {
  const RunResult r = runTool(p("left.png") + " " + p("right.png") + " " + p("out.png") + " -lidar " + p("sparse.png") +
                              " -num_disparities 32 -color " + p("color.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("fused"), std::string::npos) << r.output;
  const cv::Mat out = cv::imread(p("out.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(out.type(), CV_16UC1);
  EXPECT_EQ(out.cols, 97);
  // Disparity 6 + 0.05*50 = 8.5 px at x = 50, stored as value/256.
  EXPECT_NEAR(out.at<std::uint16_t>(30, 50) / 256.0, 8.5, 0.5);
  EXPECT_EQ(cv::imread(p("color.png")).channels(), 3);
  EXPECT_EQ(fileCount(), 6u) << "temporary files left behind";
}

TEST_F(DisparityCli, HalfScaleAndThreadsKeepTheFullSizeAndTheResult) {
  const std::string inputs = p("left.png") + " " + p("right.png") + " ";
  const std::string lidar = " -lidar " + p("sparse.png") + " -num_disparities 32";
  const RunResult half = runTool(inputs + p("half.png") + lidar + " -scale 0.5");
  ASSERT_EQ(half.exitCode, 0) << half.output;
  EXPECT_NE(half.output.find("matched at scale 0.5"), std::string::npos) << half.output;
  const cv::Mat out = cv::imread(p("half.png"), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(out.cols, 97);  // odd sizes too: the last column and row are covered
  EXPECT_EQ(out.rows, 61);
  EXPECT_NEAR(out.at<std::uint16_t>(30, 50) / 256.0, 8.5, 1.0);
  for (const std::string n : {"1", "2"}) {
    const RunResult r = runTool(inputs + p("t" + n + ".png") + lidar + " -threads " + n);
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  EXPECT_EQ(cv::countNonZero(cv::imread(p("t1.png"), cv::IMREAD_UNCHANGED) !=
                             cv::imread(p("t2.png"), cv::IMREAD_UNCHANGED)), 0);
}

TEST_F(DisparityCli, TwoFilesMeanLidarOnly) {
  const RunResult r = runTool(p("left.png") + " " + p("out.png") + " -lidar " + p("sparse.png") + " -num_disparities 32");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("lidar-only"), std::string::npos) << r.output;
}

TEST_F(DisparityCli, TheSearchRangeComesFromTheLidarUnlessFixed) {
  // The LiDAR reaches 6 + 0.05 * 96 = 10.8 px: 10.8 + 8 -> [0, 32). Printed, and the color map spans it.
  const std::string fused = p("left.png") + " " + p("right.png") + " " + p("out.png") + " -lidar " + p("sparse.png");
  const RunResult lidar = runTool(fused);
  ASSERT_EQ(lidar.exitCode, 0) << lidar.output;
  EXPECT_NE(lidar.output.find("disparity range: [0, 32) px from the LiDAR (max 10.8 px)"), std::string::npos)
      << lidar.output;
  const RunResult fixed = runTool(fused + " -num_disparities 64");
  ASSERT_EQ(fixed.exitCode, 0) << fixed.output;
  EXPECT_NE(fixed.output.find("disparity range: [0, 64) px (fixed)"), std::string::npos) << fixed.output;
  const RunResult paper = runTool(fused + " -disparity_range fixed");
  EXPECT_NE(paper.output.find("disparity range: [0, 128) px (fixed)"), std::string::npos) << paper.output;
  // -disparity_range lidar wins over -num_disparities, which is then the range without LiDAR.
  const RunResult both = runTool(fused + " -num_disparities 64 -disparity_range lidar");
  EXPECT_NE(both.output.find("disparity range: [0, 32) px from the LiDAR"), std::string::npos) << both.output;
  // Stereo only: nothing to take it from.
  const RunResult stereo = runTool(p("left.png") + " " + p("right.png") + " " + p("out.png"));
  EXPECT_NE(stereo.output.find("disparity range: [0, 128) px (fixed)"), std::string::npos) << stereo.output;
}

TEST_F(DisparityCli, ASwappedPairIsRefusedWithOrWithoutLidarUnlessTheCheckIsOff) {
  const std::string swapped = p("right.png") + " " + p("left.png") + " " + p("out.png") + " -num_disparities 32";
  expectFailure(swapped, "the stereo pair looks swapped: ");
  expectFailure(swapped, "textured pixels");
  expectFailure(swapped + " -lidar " + p("sparse.png"), "LiDAR points");
  const RunResult r = runTool(swapped + " -no_pair_check");
  ASSERT_EQ(r.exitCode, 0) << r.output;
}

TEST_F(DisparityCli, AKittiDepthPngGivenAsDisparitiesIsNamed) {
  if (!test::haveSharedData("kitti_stereo_sparse_lidar_disparity_sample")) GTEST_SKIP() << "no KITTI sample";
  const std::string dir = test::sharedDataRoot() + "/kitti_stereo_sparse_lidar_disparity_sample";
  // The sample's LiDAR disparities as a KITTI depth PNG (metres*256, F = 721.5 px * 0.54 m).
  const cv::Mat disparity = cv::imread(dir + "/sparse_lidar_disparity.png", cv::IMREAD_UNCHANGED);
  cv::Mat depth(disparity.size(), CV_16UC1, cv::Scalar(0));
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const int d = disparity.at<std::uint16_t>(y, x);
      if (d > 0) depth.at<std::uint16_t>(y, x) = cv::saturate_cast<std::uint16_t>(389.6 / (d / 256.0) * 256.0);
    }
  }
  fs::create_directories(dir_ / "proj_depth");
  write("proj_depth/0000000005.png", depth);
  const std::string pair = dir + "/left.png " + dir + "/right.png " + p("out.png");
  const RunResult right = runTool(pair + " -lidar " + dir + "/sparse_lidar_disparity.png");
  ASSERT_EQ(right.exitCode, 0) << right.output;
  EXPECT_EQ(right.output.find("Warning"), std::string::npos) << right.output;
  const RunResult wrong = runTool(pair + " -lidar " + p("proj_depth/0000000005.png"));
  EXPECT_NE(wrong.output.find("Warning: '" + p("proj_depth/0000000005.png") + "' is named like a depth map"),
            std::string::npos)
      << wrong.output;
  EXPECT_NE(wrong.output.find("as depths do"), std::string::npos) << wrong.output;
  // The disparities given as depths: the other way round.
  const RunResult swapped = runTool(pair + " -lidar_depth " + dir + "/sparse_lidar_disparity.png -fb 389.6");
  EXPECT_NE(swapped.output.find("named like a disparity map"), std::string::npos) << swapped.output;
  EXPECT_NE(swapped.output.find("as disparities do"), std::string::npos) << swapped.output;
}

TEST_F(DisparityCli, FailsLoudlyAndLeavesNoOutput) {
  const std::string lr = p("left.png") + " " + p("right.png") + " ";
  expectFailure(lr + p("out.png") + " -p1 100 -p2 50", "P2 = 50");
  expectFailure(lr + p("out.png") + " -num_disparities 100", "multiple of 16");
  expectFailure(lr + p("out.png") + " -alpha 2", "alpha = 2");
  expectFailure(lr + p("out.png") + " -alpha abc", "'abc' is not a finite number");
  expectFailure(lr + p("out.png") + " -paths", "needs a value");
  expectFailure(lr + p("out.png") + " -bogus 1", "unknown option -bogus");
  expectFailure(p("missing.png") + " " + p("right.png") + " " + p("out.png"), "missing.png': no such file");
  expectFailure(p("left.png") + " " + p("small.png") + " " + p("out.png"), "the left image is 97x61 but the right image is 97x60");
  expectFailure(p("left.png") + " " + p("out.png"), "needs -lidar or -lidar_depth");
  expectFailure(lr + p("out.png") + " -lidar " + p("left.png"), "16-bit single-channel");
  expectFailure(lr + p("out.png") + " -lidar_depth " + p("sparse.png"), "needs -fb");
  expectFailure(lr + p("out.png") + " -backend gpu", "option -backend: unknown backend 'gpu'");
  expectFailure(lr + p("out.png") + " -scale 0.7", "scale = 0.7");
  expectFailure(lr + p("out.png") + " -threads -1", "threads = -1");
  expectFailure(lr + p("out.png") + " -scale 0.5 -num_disparities 48", "numDisparities = 48");
  expectFailure(lr + p("out.png") + " -disparity_range auto", "option -disparity_range: 'auto' must be lidar or fixed");
  expectFailure(lr + p("out.jpg"), "must be a .png file");
  expectFailure(p("left.png") + " " + p("right.png") + " " + p("no_dir/out.png"), "cannot write");
  fs::create_directories(p("folder.png"));
  expectFailure(lr + p("out.png") + " -color " + p("folder.png"), "cannot write '" + p("folder.png") + "': it is a folder");
}

TEST_F(DisparityCli, NeverOverwritesAnInput) {
  const auto before = fs::file_size(p("right.png"));
  const RunResult r = runTool(p("left.png") + " " + p("right.png") + " " + p("right.png"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("refusing to overwrite an input"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(p("right.png")), before);
}

}  // namespace
}  // namespace lidar_sgm
