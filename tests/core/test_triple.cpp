// Triple-SGM (paper Sec. IV-D): a third camera b_up above the left one. The vertical census cost
// C_V, its combination with C_S, the Matcher's VerticalView API, and a scene that only the
// vertical pair can disambiguate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "backends/common/stages.hpp"
#include "lidar_sgm/eval/metrics.hpp"

namespace lidar_sgm {
namespace {

// ---------------------------------------------------------------------------------------------
// Fixed-point vertical disparity
// ---------------------------------------------------------------------------------------------

TEST(TripleSgm, VerticalDisparityRoundsDTimesRatio) {
  // ratio 0.37: 65536 * 0.37 = 24248.32 -> 24248.
  const int r37 = baselineRatio16(0.37);
  EXPECT_EQ(r37, 24248);
  EXPECT_EQ(baselineRatio16(1.0), 65536);
  // dv = (d * 24248 + 32768) >> 16, i.e. round(0.37 d) (0.37 d never hits .5 here):
  // d = 1: 57016 -> 0; d = 2: 81264 -> 1 (0.74); d = 4: 129760 -> 1 (1.48); d = 5: 154008 -> 2 (1.85);
  // d = 7: 202504 -> 3 (2.59).
  EXPECT_EQ(verticalDisparity(0, r37), 0);
  EXPECT_EQ(verticalDisparity(1, r37), 0);
  EXPECT_EQ(verticalDisparity(2, r37), 1);
  EXPECT_EQ(verticalDisparity(4, r37), 1);
  EXPECT_EQ(verticalDisparity(5, r37), 2);
  EXPECT_EQ(verticalDisparity(7, r37), 3);
  // Negative disparities floor like an arithmetic >> 16: d = -2: -48496 + 32768 = -15728 -> -1
  // (round(-0.74) = -1); d = -1: -24248 + 32768 = 8520 -> 0.
  EXPECT_EQ(verticalDisparity(-2, r37), -1);
  EXPECT_EQ(verticalDisparity(-1, r37), 0);
  // Exact half rounds up: d = 1 with ratio 0.5 (32768): 65536 >> 16 = 1.
  EXPECT_EQ(verticalDisparity(1, 32768), 1);
  EXPECT_EQ(verticalDisparity(-1, 32768), 0);  // -0.5 rounds up to 0
}

// ---------------------------------------------------------------------------------------------
// verticalCensusCost
// ---------------------------------------------------------------------------------------------

// Census images 2 x 5. Column 0: left = 0 everywhere, up(0, r) = r + 1 ones, so the cost at
// (0, y, d) is popcount(up(0, y + dv)) = y + dv + 1 and tells which up row was read.
// Column 1: left = up = 0xFF: cost 0 where the up row exists (8 if column 0 were read instead).
struct CensusColumns {
  Image<std::uint64_t> left{2, 5};
  Image<std::uint64_t> up{2, 5};
  CensusColumns() {
    for (int r = 0; r < 5; ++r) {
      left(0, r) = 0;
      up(0, r) = (std::uint64_t{1} << (r + 1)) - 1;  // r + 1 ones
      left(1, r) = 0xFF;
      up(1, r) = 0xFF;
    }
  }
};

TEST(TripleSgm, VerticalCensusCostRatio037ByHand) {
  const CensusColumns c;
  MatchingCostVolume cost(2, 5, 8);
  cpu_ref::verticalCensusCost(c.left.view(), c.up.view(), CensusType::Census9x7, baselineRatio16(0.37), 0, cost);
  // dv for d = 0..7 (see above): 0 0 1 1 1 2 2 3.
  // y = 1: d=0 -> up row 1 -> 2 ones; d=2 -> row 2 -> 3; d=5 -> row 3 -> 4; d=7 -> row 4 -> 5.
  EXPECT_EQ(cost(0, 1, 0), 2);
  EXPECT_EQ(cost(0, 1, 1), 2);
  EXPECT_EQ(cost(0, 1, 2), 3);
  EXPECT_EQ(cost(0, 1, 4), 3);
  EXPECT_EQ(cost(0, 1, 5), 4);
  EXPECT_EQ(cost(0, 1, 7), 5);
  // y = 2, d = 7: row 5 is outside the 5-row up image -> 31 (as x - d < 0 for the right image).
  EXPECT_EQ(cost(0, 2, 6), 5);   // dv 2 -> row 4
  EXPECT_EQ(cost(0, 2, 7), kNoCounterpartCensusCost);
  // y = 4 (last row): d = 1 still reads row 4 (5 ones); d = 2 (dv 1) is outside -> 31.
  EXPECT_EQ(cost(0, 4, 1), 5);
  EXPECT_EQ(cost(0, 4, 2), 31);
  // Column 1 reads its own column: 0xFF ^ 0xFF = 0 inside, 31 outside.
  EXPECT_EQ(cost(1, 1, 7), 0);
  EXPECT_EQ(cost(1, 4, 2), 31);
}

TEST(TripleSgm, VerticalCensusCostRatio1ByHand) {
  const CensusColumns c;
  MatchingCostVolume cost(2, 5, 8);
  cpu_ref::verticalCensusCost(c.left.view(), c.up.view(), CensusType::Census9x7, baselineRatio16(1.0), 0, cost);
  // ratio 1: dv = d. y = 0, d = 3 -> row 3 -> 4 ones; y = 1, d = 3 -> row 4 -> 5; d = 4 -> row 5: 31.
  EXPECT_EQ(cost(0, 0, 0), 1);
  EXPECT_EQ(cost(0, 0, 3), 4);
  EXPECT_EQ(cost(0, 1, 3), 5);
  EXPECT_EQ(cost(0, 1, 4), kNoCounterpartCensusCost);
  EXPECT_EQ(cost(0, 0, 7), kNoCounterpartCensusCost);
  EXPECT_EQ(cost(1, 0, 4), 0);
}

TEST(TripleSgm, VerticalCensusCostHonoursMinDisparity) {
  const CensusColumns c;
  MatchingCostVolume cost(2, 5, 4);
  // minDisparity -2, ratio 1: index 0 is d = -2 -> dv = -2 (the up camera would see it higher).
  // y = 3: row 1 -> 2 ones; y = 1: row -1 -> 31; index 3 (d = 1): y = 1 -> row 2 -> 3 ones.
  cpu_ref::verticalCensusCost(c.left.view(), c.up.view(), CensusType::Census9x7, 65536, -2, cost);
  EXPECT_EQ(cost(0, 3, 0), 2);
  EXPECT_EQ(cost(0, 1, 0), kNoCounterpartCensusCost);
  EXPECT_EQ(cost(0, 1, 3), 3);
  // minDisparity 5, ratio 0.37: index 0 is d = 5 -> dv 2: y = 0 -> row 2 -> 3 ones.
  cpu_ref::verticalCensusCost(c.left.view(), c.up.view(), CensusType::Census9x7, baselineRatio16(0.37), 5, cost);
  EXPECT_EQ(cost(0, 0, 0), 3);
}

TEST(TripleSgm, VerticalCensusCostCenterSymmetricIsDoubled) {
  const CensusColumns c;
  MatchingCostVolume cost(2, 5, 8);
  cpu_ref::verticalCensusCost(c.left.view(), c.up.view(), CensusType::CenterSymmetric9x7, 65536, 0, cost);
  // As in censusCost: 31-bit strings count twice; y = 0, d = 2 -> row 2 -> 3 ones -> 6. The
  // border value stays 31.
  EXPECT_EQ(cost(0, 0, 2), 6);
  EXPECT_EQ(cost(0, 0, 5), kNoCounterpartCensusCost);
}

// ---------------------------------------------------------------------------------------------
// combineCameraCosts
// ---------------------------------------------------------------------------------------------

TEST(TripleSgm, CombineCameraCostsIsTheRoundedMean) {
  MatchingCostVolume horizontal(1, 1, 6);
  MatchingCostVolume vertical(1, 1, 6);
  const int h[6] = {3, 62, 0, 0, 31, 62};
  const int v[6] = {4, 62, 1, 0, 0, 31};
  for (int d = 0; d < 6; ++d) {
    horizontal(0, 0, d) = static_cast<std::uint8_t>(h[d]);
    vertical(0, 0, d) = static_cast<std::uint8_t>(v[d]);
  }
  MatchingCostVolume combined(1, 1, 6);
  cpu_ref::combineCameraCosts(horizontal, vertical, combined);
  EXPECT_EQ(combined(0, 0, 0), 4);   // (3 + 4 + 1) >> 1 = 4 (3.5 rounds up)
  EXPECT_EQ(combined(0, 0, 1), 62);  // (62 + 62 + 1) >> 1 = 62: the range stays [0, 62]
  EXPECT_EQ(combined(0, 0, 2), 1);   // (0 + 1 + 1) >> 1 = 1
  EXPECT_EQ(combined(0, 0, 3), 0);   // (0 + 0 + 1) >> 1 = 0
  EXPECT_EQ(combined(0, 0, 4), 16);  // (31 + 0 + 1) >> 1 = 16: no right counterpart, up matches
  EXPECT_EQ(combined(0, 0, 5), 47);  // (62 + 31 + 1) >> 1 = 47
}

// ---------------------------------------------------------------------------------------------
// A scene only the vertical pair can disambiguate
// ---------------------------------------------------------------------------------------------

struct TripleScene {
  Image<std::uint8_t> left;
  Image<std::uint8_t> right;
  Image<std::uint8_t> up;
  Image<float> disparity;
  Image<std::uint8_t> exclude;  ///< no right or no up counterpart: not scored
};

// A fronto-parallel plane at disparity d. The texture repeats every `period` px along x (every
// candidate d + k * period matches the left/right pair equally well) but its rows are independent
// random values (it varies in y). Left: T(x, y); right: T(x + d, y); up camera above the left
// one: the point (x, y) appears at (x, y + d * ratio), so up(x, yu) = T(x, yu - d * ratio),
// rows interpolated linearly when d * ratio is fractional.
TripleScene makeTripleScene(int width, int height, int d, double ratio, int period, unsigned seed) {
  const double dv = d * ratio;
  const int margin = static_cast<int>(std::ceil(dv)) + 2;  // texture rows above the left image
  const test::RowTexture texture(height + margin, width + 512, period, seed);
  const auto gray = [](double v) { return static_cast<std::uint8_t>(std::lround(v)); };
  TripleScene s;
  s.left = Image<std::uint8_t>(width, height);
  s.right = Image<std::uint8_t>(width, height);
  s.up = Image<std::uint8_t>(width, height);
  s.disparity = Image<float>(width, height, static_cast<float>(d));
  s.exclude = Image<std::uint8_t>(width, height);
  for (int y = 0; y < height; ++y) {
    const double v = y + margin - dv;  // texture row the up image sees at its row y
    const int v0 = static_cast<int>(std::floor(v));
    const double t = v - v0;
    for (int x = 0; x < width; ++x) {
      s.left(x, y) = gray(texture(x, y + margin));
      s.right(x, y) = gray(texture(x + d, y + margin));
      s.up(x, y) = gray((1.0 - t) * texture(x, v0) + t * texture(x, v0 + 1));
      s.exclude(x, y) = x - d < 0 || y + dv > height - 1 ? 1 : 0;
    }
  }
  return s;
}

Parameters sceneParams() {
  Parameters p;
  p.numDisparities = 32;
  return p;
}

constexpr int kSceneWidth = 157;  // odd sizes on purpose
constexpr int kSceneHeight = 93;
constexpr int kSceneDisparity = 20;
constexpr int kScenePeriod = 8;  // candidates 4, 12, 20, 28 tie for the left/right pair

double correctShare(const Image<std::int16_t>& out, const TripleScene& s) {
  return eval::evaluateDisparity(out.view(), s.disparity.view(), s.exclude.view()).correct;
}

class PeriodicScene : public ::testing::TestWithParam<double> {};

TEST_P(PeriodicScene, ThirdCameraResolvesWhatTwoCannot) {
  const double ratio = GetParam();
  const TripleScene s = makeTripleScene(kSceneWidth, kSceneHeight, kSceneDisparity, ratio, kScenePeriod, 11);
  auto matcher = Matcher::create(Backend::CpuRef, sceneParams());
  Image<std::int16_t> two(kSceneWidth, kSceneHeight);
  Image<std::int16_t> three(kSceneWidth, kSceneHeight);

  matcher->compute(s.left.view(), s.right.view(), nullptr, two.view());
  EXPECT_EQ(toString(matcher->lastMode(), matcher->lastUsedUpCamera()), "stereo-only");
  matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), ratio}, nullptr, three.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::StereoOnly);
  EXPECT_TRUE(matcher->lastUsedUpCamera());
  EXPECT_EQ(toString(matcher->lastMode(), matcher->lastUsedUpCamera()), "stereo-only (3 cameras)");
  EXPECT_GT(matcher->lastTimings().verticalCensusCost, 0.0);

  const double correctTwo = correctShare(two, s);
  const double correctThree = correctShare(three, s);
  std::printf("  ratio %.2f: 2 cameras %.2f %% correct, 3 cameras %.2f %% correct\n", ratio, 100 * correctTwo,
              100 * correctThree);
  EXPECT_LT(correctTwo, 0.5);
  EXPECT_GT(correctThree, 0.95);
}

// 0.5: whole-row vertical shift (dv = 10); 0.37: the paper's rig (0.20 m over ~0.54 m), dv = 7.4.
INSTANTIATE_TEST_SUITE_P(Ratios, PeriodicScene, ::testing::Values(0.5, 0.37),
                         [](const ::testing::TestParamInfo<double>& param) {
                           return param.param == 0.5 ? std::string("Half") : std::string("Paper037");
                         });

TEST(TripleSgm, FusedWithLidarReportsThreeCameras) {
  const TripleScene s = makeTripleScene(kSceneWidth, kSceneHeight, kSceneDisparity, 0.5, kScenePeriod, 11);
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.0, 3);
  auto matcher = Matcher::create(Backend::CpuRef, sceneParams());
  Image<std::int16_t> out(kSceneWidth, kSceneHeight);
  matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), 0.5}, &lidar, out.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::Fused);
  EXPECT_EQ(toString(matcher->lastMode(), matcher->lastUsedUpCamera()), "fused (3 cameras)");
  EXPECT_GT(correctShare(out, s), 0.95);
  // LiDAR-only never uses cameras: no suffix.
  EXPECT_EQ(toString(MatchMode::LidarOnly, true), "lidar-only");
}

TEST(TripleSgm, EmptyVerticalViewIsBitIdenticalToTwoCameras) {
  const test::SyntheticStereo s =
      test::makeStereo(83, 61, [](double x, double y) { return 6.0 + 0.05 * x + 0.03 * y; });
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.5, 5);
  for (const LidarPoints* points : {static_cast<const LidarPoints*>(nullptr), &lidar}) {
    auto matcher = Matcher::create(Backend::CpuRef, sceneParams());
    Image<std::int16_t> reference(83, 61);
    Image<std::int16_t> viaOverload(83, 61);
    matcher->compute(s.left.view(), s.right.view(), points, reference.view());
    // A fresh matcher too, so that no buffer left by the first call could hide a difference.
    auto fresh = Matcher::create(Backend::CpuRef, sceneParams());
    fresh->compute(s.left.view(), s.right.view(), VerticalView{}, points, viaOverload.view());
    EXPECT_FALSE(fresh->lastUsedUpCamera());
    EXPECT_EQ(fresh->lastMode(), points ? MatchMode::Fused : MatchMode::StereoOnly);
    EXPECT_EQ(fresh->lastTimings().verticalCensusCost, 0.0);
    long differing = 0;
    for (int y = 0; y < 61; ++y) {
      for (int x = 0; x < 83; ++x) differing += reference(x, y) != viaOverload(x, y) ? 1 : 0;
    }
    EXPECT_EQ(differing, 0) << (points ? "fused" : "stereo-only");
  }
}

TEST(TripleSgm, UpCameraFlagIsClearedByALaterTwoCameraFrame) {
  const TripleScene s = makeTripleScene(kSceneWidth, kSceneHeight, kSceneDisparity, 0.5, kScenePeriod, 11);
  auto matcher = Matcher::create(Backend::CpuRef, sceneParams());
  Image<std::int16_t> out(kSceneWidth, kSceneHeight);
  matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), 0.5}, nullptr, out.view());
  EXPECT_TRUE(matcher->lastUsedUpCamera());
  matcher->compute(s.left.view(), s.right.view(), nullptr, out.view());
  EXPECT_FALSE(matcher->lastUsedUpCamera());
  EXPECT_EQ(matcher->lastTimings().verticalCensusCost, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Validation
// ---------------------------------------------------------------------------------------------

void expectMessage(const std::function<void()>& call, const std::string& text) {
  try {
    call();
    FAIL() << "expected std::invalid_argument containing '" << text << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(TripleSgm, RejectsBadUpInputsWithAMessageNamingTheProblem) {
  const TripleScene s = makeTripleScene(40, 30, 5, 0.5, 0, 3);
  auto matcher = Matcher::create(Backend::CpuRef, sceneParams());
  Image<std::int16_t> out(40, 30);
  const Image<std::uint8_t> shorter(40, 29);
  const Image<std::uint16_t> up16(40, 30);
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.0, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();

  expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), VerticalView{shorter.view(), 0.5}, nullptr,
                                       out.view()); },
                "left and up images differ in size: left 40x30, up 40x29");
  expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), VerticalView{up16.view(), 0.5}, nullptr,
                                       out.view()); },
                "left and up images differ in bit depth");
  for (double ratio : {0.0, nan, 5.0, -0.5, std::numeric_limits<double>::infinity()}) {
    expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), ratio}, nullptr,
                                         out.view()); },
                  "baselineRatio");
    expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), ratio}, nullptr,
                                         out.view()); },
                  "(0, 4]");
  }
  // Up without right: with LiDAR (would otherwise be LiDAR-only) and without.
  expectMessage([&] { matcher->compute(s.left.view(), GrayImageView(), VerticalView{s.up.view(), 0.5}, &lidar,
                                       out.view()); },
                "no up-only mode");
  expectMessage([&] { matcher->compute(s.left.view(), GrayImageView(), VerticalView{s.up.view(), 0.5}, nullptr,
                                       out.view()); },
                "needs a right image");
  // A ratio without an up image is a mistake, not "two cameras".
  expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), VerticalView{GrayImageView(), 0.5}, nullptr,
                                       out.view()); },
                "no up image");
  // The boundary 4 is accepted; the matcher is usable after the rejections.
  matcher->compute(s.left.view(), s.right.view(), VerticalView{s.up.view(), 4.0}, nullptr, out.view());
  EXPECT_TRUE(matcher->lastUsedUpCamera());
}

}  // namespace
}  // namespace lidar_sgm
