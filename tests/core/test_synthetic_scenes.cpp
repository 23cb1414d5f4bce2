// End-to-end accuracy on stereograms with exactly known disparity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/eval/metrics.hpp"

namespace lidar_sgm {
namespace {

struct Outcome {
  eval::DisparityMetrics metrics;
  MatchMode mode;
  double withinHalfPixel;  ///< share of scored pixels with |error| < 0.5 px (missing = not)
};

double shareWithinHalfPixel(const Image<std::int16_t>& estimate, const Image<float>& gt,
                           ImageView<const std::uint8_t> exclude) {
  long scored = 0;
  long good = 0;
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      if (exclude(x, y) != 0) continue;
      ++scored;
      const std::int16_t e = estimate(x, y);
      if (e != kInvalidDisparity && std::abs(e / static_cast<double>(kDisparityScale) - gt(x, y)) < 0.5) ++good;
    }
  }
  return static_cast<double>(good) / static_cast<double>(scored);
}

Outcome match(const test::SyntheticStereo& s, const LidarPoints* lidar, bool stereo, const Parameters& p,
              ImageView<const std::uint8_t> exclude) {
  auto matcher = Matcher::create(Backend::CpuRef, p);
  Image<std::int16_t> out(s.left.width(), s.left.height());
  matcher->compute(s.left.view(), stereo ? GrayImageView(s.right.view()) : GrayImageView(), lidar, out.view());
  return {eval::evaluateDisparity(out.view(), s.disparity.view(), exclude), matcher->lastMode(),
          shareWithinHalfPixel(out, s.disparity, exclude)};
}

void print(const char* name, const Outcome& r) {
  const eval::DisparityMetrics& m = r.metrics;
  std::printf("  %-28s correct %6.2f %%  RMSE %.3f px  density %6.2f %%  within 0.5 px %6.2f %%\n", name,
              100 * m.correct, m.rmse, 100 * m.density, 100 * r.withinHalfPixel);
}

// Odd sizes on purpose (no multiple of 16, 32 or 64 anywhere).
constexpr int kWidth = 631;
constexpr int kHeight = 479;

struct PlaneCase {
  const char* name;
  const char* slug;
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
  print(c.name, r);
  EXPECT_EQ(r.mode, MatchMode::StereoOnly);
  // RMSE is over the correct pixels; with > 99 % correct, nearly every pixel is within it.
  EXPECT_GT(r.metrics.correct, 0.99);
  EXPECT_LT(r.metrics.rmse, 0.5);
  EXPECT_GT(r.metrics.density, 0.99);
}

INSTANTIATE_TEST_SUITE_P(Planes, RandomDotStereogram,
                         ::testing::Values(PlaneCase{"fronto-parallel 17.3 px", "FrontoParallel", 17.3, 0.0, 0.0},
                                           PlaneCase{"slanted in x (8..46 px)", "SlantedX", 8.0, 0.06, 0.0},
                                           PlaneCase{"slanted in x and y", "SlantedXY", 10.0, 0.03, 0.04}),
                         [](const ::testing::TestParamInfo<PlaneCase>& paramInfo) {
                           return std::string(paramInfo.param.slug);
                         });

TEST(LidarOnly, RecoversASlantedPlaneFromAFivePercentSample) {
  const test::SyntheticStereo s =
      test::makeStereo(kWidth, kHeight, [](double x, double y) { return 12.0 + 0.03 * x + 0.02 * y; });
  Image<std::uint8_t> input;
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.0, 11, &input);
  Parameters p;
  p.numDisparities = 64;
  const Outcome r = match(s, &lidar, false, p, input.view());
  print("LiDAR-only, 5 % exact", r);
  EXPECT_EQ(r.mode, MatchMode::LidarOnly);
  EXPECT_GT(r.metrics.correct, 0.99);
  EXPECT_LT(r.metrics.rmse, 0.5);
  EXPECT_GT(r.metrics.density, 0.999);  // no LR check without a right image
}

// A texture repeating every 12 px makes stereo ambiguous (several disparities match equally);
// a sparse, noisy LiDAR is unambiguous but coarse. Fusion must beat both: more pixels correct
// than stereo, and more pixels within 0.5 px and a lower RMSE than either (at 3 px, LiDAR-only
// interpolation of a smooth plane is already ~100 % correct, so the 3 px rate cannot separate them).
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
  print("stereo-only (periodic)", stereo);
  print("LiDAR-only (2 %, 0.8 px)", lidarOnly);
  print("fused alpha 0.7", fused);
  EXPECT_EQ(fused.mode, MatchMode::Fused);
  EXPECT_LT(stereo.metrics.correct, 0.9) << "the scene must be ambiguous for stereo, or the test proves nothing";
  EXPECT_GT(fused.metrics.correct, stereo.metrics.correct + 0.05);
  EXPECT_GT(fused.withinHalfPixel, lidarOnly.withinHalfPixel + 0.02);
  EXPECT_GT(fused.withinHalfPixel, stereo.withinHalfPixel);
  EXPECT_LT(fused.metrics.rmse, lidarOnly.metrics.rmse);
  EXPECT_GT(fused.metrics.correct, 0.99);
}

}  // namespace
}  // namespace lidar_sgm
