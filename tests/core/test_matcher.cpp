#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace {

Parameters smallParams() {
  Parameters p;
  p.numDisparities = 32;
  return p;
}

void expectMessage(const std::function<void()>& call, const std::string& text) {
  try {
    call();
    FAIL() << "expected std::invalid_argument containing '" << text << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(Matcher, RejectsBadInputsWithAMessageNamingTheProblem) {
  auto matcher = Matcher::create(Backend::CpuRef, smallParams());
  const test::SyntheticStereo s = test::makeStereo(40, 30, [](double, double) { return 5.0; });
  const Image<std::uint8_t> smaller(39, 30);
  const LidarPoints lidar(40, 30, {{3, 3, 80}});
  const LidarPoints otherLidar(20, 30, {{3, 3, 80}});
  Image<std::int16_t> out(40, 30);
  Image<std::int16_t> wrongOut(41, 30);
  expectMessage([&] { matcher->compute(s.left.view(), smaller.view(), nullptr, out.view()); },
                "differ in size: left 40x30, right 39x30");
  expectMessage([&] { matcher->compute(GrayImageView(), s.right.view(), nullptr, out.view()); },
                "left image is empty");
  expectMessage([&] { matcher->compute(s.left.view(), GrayImageView(), nullptr, out.view()); },
                "no input to match");
  expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), &otherLidar, out.view()); },
                "LiDAR points are for a 20x30 image");
  expectMessage([&] { matcher->compute(s.left.view(), GrayImageView(), &otherLidar, out.view()); },
                "LiDAR points are for a 20x30 image but the left image is 40x30");
  expectMessage([&] { matcher->compute(s.left.view(), s.right.view(), &lidar, wrongOut.view()); },
                "output disparity image is 41x30");
  const Image<std::uint16_t> right16(40, 30);
  expectMessage([&] { matcher->compute(s.left.view(), right16.view(), nullptr, out.view()); }, "bit depth");
}

TEST(Matcher, ModeFollowsTheInputs) {
  auto matcher = Matcher::create(Backend::CpuRef, smallParams());
  const test::SyntheticStereo s = test::makeStereo(48, 24, [](double, double) { return 6.0; });
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.1, 0.0, 3);
  const LidarPoints none(48, 24, {});
  Image<std::int16_t> out(48, 24);
  matcher->compute(s.left.view(), s.right.view(), nullptr, out.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::StereoOnly);
  matcher->compute(s.left.view(), s.right.view(), &none, out.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::StereoOnly);
  matcher->compute(s.left.view(), s.right.view(), &lidar, out.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::Fused);
  matcher->compute(GrayImageView(), GrayImageView(), &lidar, out.view());
  EXPECT_EQ(matcher->lastMode(), MatchMode::LidarOnly);
}

// Padded strides on every image (inputs and output) must not change a single pixel.
TEST(Matcher, PaddedStridesGiveTheSameResult) {
  const int w = 63;
  const int h = 37;
  const int stride = 80;
  const test::SyntheticStereo s = test::makeStereo(w, h, [](double x, double) { return 4.0 + 0.05 * x; });
  const LidarPoints lidar = test::sampleLidar(s.disparity, 0.05, 0.2, 5);
  std::vector<std::uint8_t> leftPadded(stride * h, 77);
  std::vector<std::uint8_t> rightPadded(stride * h, 201);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      leftPadded[y * stride + x] = s.left(x, y);
      rightPadded[y * stride + x] = s.right(x, y);
    }
  }
  std::vector<std::int16_t> outPadded(stride * h, 999);
  auto matcher = Matcher::create(Backend::CpuRef, smallParams());
  Image<std::int16_t> dense(w, h);
  matcher->compute(s.left.view(), s.right.view(), &lidar, dense.view());
  matcher->compute(ImageView<const std::uint8_t>(leftPadded.data(), w, h, stride),
                   ImageView<const std::uint8_t>(rightPadded.data(), w, h, stride), &lidar,
                   ImageView<std::int16_t>(outPadded.data(), w, h, stride));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) ASSERT_EQ(outPadded[y * stride + x], dense(x, y)) << x << "," << y;
    for (int x = w; x < stride; ++x) ASSERT_EQ(outPadded[y * stride + x], 999) << "wrote into padding";
  }
}

// Buffers are reused between frames: a second frame of another size, then the first again,
// must give exactly the first result.
TEST(Matcher, ReusedBuffersDoNotLeakBetweenFrames) {
  auto matcher = Matcher::create(Backend::CpuRef, smallParams());
  const test::SyntheticStereo a = test::makeStereo(50, 30, [](double, double) { return 7.0; }, 0, 1);
  const test::SyntheticStereo b = test::makeStereo(70, 41, [](double, double) { return 12.0; }, 0, 2);
  const LidarPoints lidarA = test::sampleLidar(a.disparity, 0.05, 0.0, 1);
  Image<std::int16_t> first(50, 30);
  Image<std::int16_t> other(70, 41);
  Image<std::int16_t> again(50, 30);
  matcher->compute(a.left.view(), a.right.view(), &lidarA, first.view());
  matcher->compute(b.left.view(), b.right.view(), nullptr, other.view());
  matcher->compute(a.left.view(), a.right.view(), &lidarA, again.view());
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 50; ++x) ASSERT_EQ(first(x, y), again(x, y));
  }
}

// Census compares intensities only: a 16-bit copy (x257) must match exactly like the 8-bit one.
TEST(Matcher, SixteenBitImagesMatchLikeEightBit) {
  const test::SyntheticStereo s = test::makeStereo(60, 30, [](double, double) { return 9.0; });
  Image<std::uint16_t> left16(60, 30);
  Image<std::uint16_t> right16(60, 30);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 60; ++x) {
      left16(x, y) = static_cast<std::uint16_t>(s.left(x, y) * 257);
      right16(x, y) = static_cast<std::uint16_t>(s.right(x, y) * 257);
    }
  }
  auto matcher = Matcher::create(Backend::CpuRef, smallParams());
  Image<std::int16_t> out8(60, 30);
  Image<std::int16_t> out16(60, 30);
  matcher->compute(s.left.view(), s.right.view(), nullptr, out8.view());
  matcher->compute(left16.view(), right16.view(), nullptr, out16.view());  // mutable views convert too
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 60; ++x) ASSERT_EQ(out8(x, y), out16(x, y));
  }
}

}  // namespace
}  // namespace lidar_sgm

namespace lidar_sgm {
namespace {

int validPixels(const Image<std::int16_t>& d) {
  int n = 0;
  for (int y = 0; y < d.height(); ++y) {
    for (int x = 0; x < d.width(); ++x) n += d(x, y) != kInvalidDisparity ? 1 : 0;
  }
  return n;
}

TEST(Matcher, FusedModeChecksLeftRightOnlyWhenAskedTo) {
  // The right image's right half is replaced by unrelated noise, and the LiDAR covers the left
  // half only: on the right half, matching is arbitrary and the left-right check finds
  // inconsistent pixels.
  test::SyntheticStereo s = test::makeStereo(96, 48, [](double, double) { return 10.0; }, 0, 4);
  const test::SyntheticStereo other = test::makeStereo(96, 48, [](double, double) { return 10.0; }, 0, 99);
  for (int y = 0; y < 48; ++y) {
    for (int x = 48; x < 96; ++x) s.right(x, y) = other.right(x, y);
  }
  std::vector<LidarSample> samples;
  for (int y = 0; y < 48; y += 4) {
    for (int x = 0; x < 48; x += 2) samples.push_back({x, y, 160});  // exact: 10 px
  }
  const LidarPoints lidar(96, 48, samples);
  Parameters params;
  params.numDisparities = 32;
  Image<std::int16_t> byDefault(96, 48), noCheck(96, 48), checked(96, 48);
  Matcher::create(Backend::CpuRef, params)->compute(s.left.view(), s.right.view(), &lidar, byDefault.view());
  params.lrCheck = false;
  Matcher::create(Backend::CpuRef, params)->compute(s.left.view(), s.right.view(), &lidar, noCheck.view());
  params.lrCheck = true;
  params.lrCheckWithLidar = true;
  Matcher::create(Backend::CpuRef, params)->compute(s.left.view(), s.right.view(), &lidar, checked.view());
  // The default (no check in fused mode) is bit-identical to switching the check off.
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 96; ++x) ASSERT_EQ(byDefault(x, y), noCheck(x, y)) << x << "," << y;
  }
  EXPECT_EQ(validPixels(byDefault), 96 * 48);
  EXPECT_LT(validPixels(checked), validPixels(byDefault));
}

}  // namespace
}  // namespace lidar_sgm
