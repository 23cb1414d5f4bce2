// Protocol P1 of EVALUATION.md on real KITTI 2015 frames: GT-sampled 64-beam LiDAR, scored on
// the GT pixels that were not given as input. KITTI's GT is itself accumulated LiDAR, so this
// protocol favours the LiDAR; it is reported as such.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/test_data.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/simulated_lidar.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {

const char* kFolder = "kitti_stereo2015_training_sample";

class KittiP1 : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!test::haveSharedData(kFolder)) GTEST_SKIP() << "no " << kFolder << " under " << test::sharedDataRoot();
  }
};

TEST_P(KittiP1, FusedBeatsStereoAndMeetsTheTargets) {
  const std::string root = test::sharedDataRoot() + "/" + kFolder + "/";
  const std::string id = GetParam();
  const cv::Mat left = io::readGrayImage(root + "image_2/" + id + ".png");
  const cv::Mat right = io::readGrayImage(root + "image_3/" + id + ".png");
  const Image<float> gt = io::readKittiDisparityFloat(root + "disp_occ_0/" + id + ".png");
  Image<std::uint8_t> inputMask;
  const LidarPoints lidar = eval::simulateLidarFromGroundTruth(gt.view(), {}, inputMask);

  auto matcher = Matcher::create(Backend::CpuRef, Parameters{});
  Image<std::int16_t> out(left.cols, left.rows);
  auto run = [&](bool stereo, bool withLidar) {
    matcher->compute(io::grayView(left), stereo ? io::grayView(right) : GrayImageView(),
                     withLidar ? &lidar : nullptr, out.view());
    const eval::DisparityMetrics m = eval::evaluateDisparity(out.view(), gt.view(), inputMask.view());
    std::printf("  %s %-12s correct %6.2f %%  RMSE %.3f px  D1 %5.2f %%  density %6.2f %%  [%.0f ms, cpu_ref]\n",
                id.c_str(), toString(matcher->lastMode()).c_str(), 100 * m.correct, m.rmse, 100 * m.d1,
                100 * m.density, matcher->lastTimings().total());
    return m;
  };
  std::printf("  %zu simulated LiDAR points (%.2f %% of pixels)\n", lidar.size(),
              100.0 * static_cast<double>(lidar.size()) / (left.cols * left.rows));
  const eval::DisparityMetrics stereo = run(true, false);
  const eval::DisparityMetrics lidarOnly = run(false, true);
  const eval::DisparityMetrics fused = run(true, true);

  EXPECT_GE(stereo.correct, 0.80);
  EXPECT_GE(fused.correct, 0.95);
  EXPECT_LE(fused.rmse, 0.7);
  EXPECT_GE(fused.density, 0.97);
  EXPECT_GT(fused.correct, stereo.correct);
  EXPECT_LT(fused.rmse, stereo.rmse);
  EXPECT_GT(lidarOnly.density, 0.999);
}

INSTANTIATE_TEST_SUITE_P(Kitti2015, KittiP1, ::testing::Values("000000_10", "000001_10"),
                         [](const ::testing::TestParamInfo<std::string>& paramInfo) { return "frame" + paramInfo.param; });

}  // namespace
}  // namespace lidar_sgm
