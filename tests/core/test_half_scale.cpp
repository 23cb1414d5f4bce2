// The paper's half-scale mode (Sec. IV-F): inputs scaled down in the core, any backend matches
// the half-size frame, the disparity comes back at full resolution with values x2.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/synthetic_stereo.hpp"
#include "core/half_scale.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace {

TEST(HalfScale, BoxAverageRoundsHalfUpAndRepeatsTheOddEdge) {
  Image<std::uint8_t> in(3, 3);
  const std::uint8_t values[9] = {0, 1, 10, 2, 3, 20, 100, 101, 255};
  for (int i = 0; i < 9; ++i) in(i % 3, i / 3) = values[i];
  Image<std::uint8_t> out;
  downscaleHalf(std::as_const(in).view(), out);
  ASSERT_EQ(out.width(), 2);
  ASSERT_EQ(out.height(), 2);
  EXPECT_EQ(out(0, 0), 2);    // (0 + 1 + 2 + 3 + 2) >> 2 = 8 >> 2
  EXPECT_EQ(out(1, 0), 15);   // (10 + 10 + 20 + 20 + 2) >> 2 = 62 >> 2
  EXPECT_EQ(out(0, 1), 101);  // (100 + 101 + 100 + 101 + 2) >> 2 = 404 >> 2
  EXPECT_EQ(out(1, 1), 255);  // one pixel repeated four times
}

TEST(HalfScale, LidarPointsMoveToTheHalfPixelWithHalfTheDisparity) {
  const LidarPoints full(10, 7, {{5, 3, 33}, {4, 2, 1}, {9, 6, 160}});
  const LidarPoints half = halveLidarPoints(full);
  EXPECT_EQ(half.width(), 5);
  EXPECT_EQ(half.height(), 4);
  ASSERT_EQ(half.count(2, 1), 2);  // (5, 3) and (4, 2) both land in (2, 1)
  std::vector<int> d(half.begin(2, 1), half.end(2, 1));
  std::sort(d.begin(), d.end());
  EXPECT_EQ(d, (std::vector<int>{1, 17}));  // 1/16 px stays in front of the camera; 33 -> 16.5 -> 17
  ASSERT_EQ(half.count(4, 3), 1);
  EXPECT_EQ(*half.begin(4, 3), 80);
}

TEST(HalfScale, UpscaledDisparityDoublesValuesAndKeepsInvalid) {
  Image<std::int16_t> half(2, 2);
  half(0, 0) = 16;
  half(1, 0) = kInvalidDisparity;
  half(0, 1) = 40;
  half(1, 1) = -3;
  Image<std::int16_t> full(3, 3);
  upscaleDisparity(std::as_const(half).view(), full.view());
  EXPECT_EQ(full(0, 0), 32);
  EXPECT_EQ(full(1, 1), 32);
  EXPECT_EQ(full(2, 0), kInvalidDisparity);
  EXPECT_EQ(full(0, 2), 80);
  EXPECT_EQ(full(2, 2), -6);
}

// The resampling splits its rows among threads: the same images on any count, at odd and even
// sizes (the last full row of an odd height is an even one, with no row below it).
TEST(HalfScale, ResamplingIsTheSameOnAnyThreadCount) {
  for (const auto& [width, height] : {std::pair{37, 23}, std::pair{40, 18}, std::pair{5, 1}}) {
    Image<std::uint8_t> in8(width, height);
    Image<std::uint16_t> in16(width, height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        in8(x, y) = static_cast<std::uint8_t>((x * 37 + y * 91) % 256);
        in16(x, y) = static_cast<std::uint16_t>((x * 3001 + y * 977) % 65536);
      }
    }
    Image<std::int16_t> half(halfSize(width), halfSize(height));
    Image<std::uint8_t> halfMask(halfSize(width), halfSize(height));
    for (int y = 0; y < half.height(); ++y) {
      for (int x = 0; x < half.width(); ++x) {
        half(x, y) = (x + y) % 5 == 0 ? kInvalidDisparity : static_cast<std::int16_t>(x * 7 - y * 3);
        halfMask(x, y) = static_cast<std::uint8_t>(x * 11 + y);
      }
    }
    Image<std::uint8_t> down8One, down8;
    Image<std::uint16_t> down16One, down16;
    Image<std::int16_t> upOne(width, height), up(width, height);
    Image<std::uint8_t> maskOne(width, height), mask(width, height);
    downscaleHalf(std::as_const(in8).view(), down8One, 1);
    downscaleHalf(std::as_const(in16).view(), down16One, 1);
    upscaleDisparity(std::as_const(half).view(), upOne.view(), 1);
    upscaleMask(std::as_const(halfMask).view(), maskOne.view(), 1);
    EXPECT_EQ(upOne(width - 1, height - 1), half(halfSize(width) - 1, halfSize(height) - 1) == kInvalidDisparity
                                                ? kInvalidDisparity
                                                : 2 * half(halfSize(width) - 1, halfSize(height) - 1));
    for (const int threads : {2, 3, 7}) {
      downscaleHalf(std::as_const(in8).view(), down8, threads);
      downscaleHalf(std::as_const(in16).view(), down16, threads);
      up.fill(0);
      mask.fill(0);
      upscaleDisparity(std::as_const(half).view(), up.view(), threads);
      upscaleMask(std::as_const(halfMask).view(), mask.view(), threads);
      const auto same = [](const auto& a, const auto& b) {
        if (a.width() != b.width() || a.height() != b.height()) return false;
        for (int y = 0; y < a.height(); ++y) {
          for (int x = 0; x < a.width(); ++x) {
            if (a(x, y) != b(x, y)) return false;
          }
        }
        return true;
      };
      EXPECT_TRUE(same(down8One, down8)) << width << "x" << height << ", " << threads << " threads";
      EXPECT_TRUE(same(down16One, down16)) << width << "x" << height << ", " << threads << " threads";
      EXPECT_TRUE(same(upOne, up)) << width << "x" << height << ", " << threads << " threads";
      EXPECT_TRUE(same(maskOne, mask)) << width << "x" << height << ", " << threads << " threads";
    }
  }
}

// The matcher at scale 0.5 is exactly: scale the inputs down, match with half the search range,
// scale the disparity up. Checked for every built backend against cpu_ref's pieces.
TEST(HalfScale, MatcherEqualsTheHandMadeHalfScalePipeline) {
  const test::SyntheticStereo s = test::makeStereo(131, 63, [](double x, double) { return 12.0 + x / 40.0; });
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.2, 3);
  Parameters full;
  full.numDisparities = 64;
  full.minDisparity = 2;
  full.scale = 0.5f;
  Parameters half = full;
  half.numDisparities = 32;
  half.minDisparity = 1;
  half.scale = 1.0f;
  Image<std::uint8_t> left, right;
  downscaleHalf(std::as_const(s.left).view(), left);
  downscaleHalf(std::as_const(s.right).view(), right);
  const LidarPoints halfLidar = halveLidarPoints(lidar);
  Image<std::int16_t> halfOut(left.width(), left.height());
  Matcher::create(Backend::CpuRef, half)->compute(std::as_const(left).view(), std::as_const(right).view(), &halfLidar,
                                                  halfOut.view());
  Image<std::int16_t> expected(131, 63);
  upscaleDisparity(std::as_const(halfOut).view(), expected.view());
  for (Backend backend : {Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
    if (!isAvailable(backend)) continue;
    auto matcher = Matcher::create(backend, full);
    Image<std::int16_t> out(131, 63);
    matcher->compute(std::as_const(s.left).view(), std::as_const(s.right).view(), &lidar, out.view());
    int differences = 0;
    for (int y = 0; y < 63; ++y) {
      for (int x = 0; x < 131; ++x) differences += out(x, y) != expected(x, y) ? 1 : 0;
    }
    EXPECT_EQ(differences, 0) << toString(backend);
    EXPECT_EQ(matcher->lidarSupport().width, 131);
    EXPECT_GT(matcher->lastRescaleMs(), 0.0);
  }
}

TEST(HalfScale, RecoversTheDisparityOfASlantedPlane) {
  const test::SyntheticStereo s = test::makeStereo(240, 120, [](double x, double) { return 20.0 + x / 30.0; });
  Parameters params;
  params.numDisparities = 64;
  params.scale = 0.5f;
  Image<std::int16_t> out(240, 120);
  Matcher::create(Backend::Auto, params)->compute(std::as_const(s.left).view(), std::as_const(s.right).view(), nullptr,
                                                  out.view());
  int within = 0;
  int scored = 0;
  for (int y = 8; y < 112; ++y) {
    for (int x = 40; x < 232; ++x) {
      ++scored;
      if (out(x, y) != kInvalidDisparity && std::abs(out(x, y) / 16.0 - s.disparity(x, y)) < 1.0) ++within;
    }
  }
  EXPECT_GT(within, scored * 9 / 10);
}

TEST(HalfScale, ImpossibleScalesAreRejectedByName) {
  Parameters p;
  p.scale = 0.7f;
  EXPECT_NE(validationError(p).find("scale"), std::string::npos);
  p.scale = 0.5f;
  p.numDisparities = 48;
  EXPECT_NE(validationError(p).find("multiple of 32 at scale 0.5"), std::string::npos);
  p.numDisparities = 64;
  p.minDisparity = 3;
  EXPECT_NE(validationError(p).find("even at scale 0.5"), std::string::npos);
  p.minDisparity = 4;
  EXPECT_EQ(validationError(p), "");
  p.threads = -1;
  EXPECT_NE(validationError(p).find("threads"), std::string::npos);
  EXPECT_THROW(Matcher::create(Backend::Auto, p), std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
