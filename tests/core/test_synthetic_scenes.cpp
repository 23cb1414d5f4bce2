// End-to-end accuracy on stereograms with exactly known disparity.
#include <gtest/gtest.h>

#include <cstdio>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/eval/metrics.hpp"

namespace lidar_sgm {
namespace {

struct Outcome {
  eval::DisparityMetrics metrics;
  MatchMode mode;
};

Outcome match(const test::SyntheticStereo& s, const LidarPoints* lidar, bool stereo, const Parameters& p,
              ImageView<const std::uint8_t> exclude) {
  auto matcher = Matcher::create(Backend::CpuRef, p);
  Image<std::int16_t> out(s.left.width(), s.left.height());
  matcher->compute(s.left.view(), stereo ? GrayImageView(s.right.view()) : GrayImageView(), lidar, out.view());
  return {eval::evaluateDisparity(out.view(), s.disparity.view(), exclude), matcher->lastMode()};
}

void print(const char* name, const eval::DisparityMetrics& m) {
  std::printf("  %-28s correct %6.2f %%  RMSE %.3f px  density %6.2f %%\n", name, 100 * m.correct, m.rmse,
              100 * m.density);
}

// Odd sizes on purpose (no multiple of 16, 32 or 64 anywhere).
constexpr int kWidth = 631;
constexpr int kHeight = 479;

struct PlaneCase {
  const char* name;
  double d0, dx, dy;
};

class RandomDotStereogram : public ::testing::TestWithParam<PlaneCase> {};

TEST_P(RandomDotStereogram, StereoOnlyRecoversThePlaneToHalfAPixel) {
  const PlaneCase c = GetParam();
  const test::SyntheticStereo s =
      test::makeStereo(kWidth, kHeight, [c](double x, double y) { return c.d0 + c.dx * x + c.dy * y; });
  Parameters p;
  p.numDisparities = 64;
  const Outcome r = match(s, nullptr, true, p, s.occluded.view());
  print(c.name, r.metrics);
  EXPECT_EQ(r.mode, MatchMode::StereoOnly);
  // RMSE over all non-occluded pixels, not only the correct ones: nothing may be far off.
  EXPECT_GT(r.metrics.correct, 0.99);
  EXPECT_LT(r.metrics.rmse, 0.5);
  EXPECT_GT(r.metrics.density, 0.99);
}

INSTANTIATE_TEST_SUITE_P(Planes, RandomDotStereogram,
                         ::testing::Values(PlaneCase{"fronto-parallel 17.3 px", 17.3, 0.0, 0.0},
                                           PlaneCase{"slanted in x (8..46 px)", 8.0, 0.06, 0.0},
                                           PlaneCase{"slanted in x and y", 10.0, 0.03, 0.04}));

TEST(LidarOnly, RecoversASlantedPlaneFromAFivePercentSample) {
  const test::SyntheticStereo s =
      test::makeStereo(kWidth, kHeight, [](double x, double y) { return 12.0 + 0.03 * x + 0.02 * y; });
  Image<std::uint8_t> input;
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.0, 11, &input);
  Parameters p;
  p.numDisparities = 64;
  const Outcome r = match(s, &lidar, false, p, input.view());
  print("LiDAR-only, 5 % exact", r.metrics);
  EXPECT_EQ(r.mode, MatchMode::LidarOnly);
  EXPECT_GT(r.metrics.correct, 0.99);
  EXPECT_LT(r.metrics.rmse, 0.5);
  EXPECT_GT(r.metrics.density, 0.999);  // no LR check without a right image
}

// A texture repeating every 12 px makes stereo ambiguous (several disparities match equally);
// a sparse, noisy LiDAR is unambiguous but coarse. Fusion must beat both.
TEST(Fusion, BeatsStereoOnlyAndLidarOnlyOnRepeatedTextureWithSparseLidar) {
  const test::SyntheticStereo s = test::makeStereo(
      kWidth, kHeight, [](double x, double y) { return 14.0 + 0.025 * x + 0.015 * y; }, /*period=*/12);
  Image<std::uint8_t> input;
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.02, 0.8, 21, &input);
  Image<std::uint8_t> exclude(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) exclude(x, y) = input(x, y) | s.occluded(x, y);
  }
  Parameters p;
  p.numDisparities = 64;
  const Outcome stereo = match(s, nullptr, true, p, exclude.view());
  const Outcome lidarOnly = match(s, &lidar, false, p, exclude.view());
  const Outcome fused = match(s, &lidar, true, p, exclude.view());
  print("stereo-only (periodic)", stereo.metrics);
  print("LiDAR-only (2 %, 0.8 px)", lidarOnly.metrics);
  print("fused alpha 0.7", fused.metrics);
  EXPECT_EQ(fused.mode, MatchMode::Fused);
  EXPECT_LT(stereo.metrics.correct, 0.9) << "the scene must be ambiguous for stereo, or the test proves nothing";
  EXPECT_GT(fused.metrics.correct, stereo.metrics.correct + 0.05);
  EXPECT_GE(fused.metrics.correct, lidarOnly.metrics.correct);
  EXPECT_LT(fused.metrics.rmse, lidarOnly.metrics.rmse);
}

}  // namespace
}  // namespace lidar_sgm
