// The check of a stereo pair's orientation: a pair given the right way round passes, the same
// pair swapped is refused by the Densifier with a message naming the likely swap, and the check
// can be turned off.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 200;
constexpr int kHeight = 80;

/// A slanted plane, 12 px at the left border to 22 px at the right one.
double plane(double x, double /*y*/) { return 12.0 + 0.05 * x; }

std::vector<LidarSample> lidarOf(const test::SyntheticStereo& s) {
  std::vector<LidarSample> samples;
  for (int y = 4; y < kHeight; y += 4) {
    for (int x = 1; x < kWidth; x += 2) samples.push_back({x, y, static_cast<int>(s.disparity(x, y) * 16 + 0.5f)});
  }
  return samples;
}

Image<std::uint16_t> times257(const Image<std::uint8_t>& image) {
  Image<std::uint16_t> out(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) out(x, y) = static_cast<std::uint16_t>(image(x, y) * 257);
  }
  return out;
}

TEST(PairOrientation, TheLidarTellsAGivenPairFromASwappedOne) {
  const test::SyntheticStereo s = test::makeStereo(kWidth, kHeight, plane);
  const std::vector<LidarSample> lidar = lidarOf(s);
  const PairOrientation given = pairOrientationFromLidar(s.left.view(), s.right.view(), lidar);
  EXPECT_TRUE(given.fromLidar);
  EXPECT_GT(given.tested, 1000u);
  EXPECT_GT(given.givenWins, given.tested * 9 / 10) << given.describe();
  EXPECT_FALSE(given.looksSwapped()) << given.describe();
  const PairOrientation swapped = pairOrientationFromLidar(s.right.view(), s.left.view(), lidar);
  EXPECT_GT(swapped.swappedWins, 10 * swapped.givenWins) << swapped.describe();
  EXPECT_TRUE(swapped.looksSwapped()) << swapped.describe();
  // At 16 bit the same.
  const Image<std::uint16_t> left16 = times257(s.left);
  const Image<std::uint16_t> right16 = times257(s.right);
  EXPECT_FALSE(pairOrientationFromLidar(left16.view(), right16.view(), lidar).looksSwapped());
  EXPECT_TRUE(pairOrientationFromLidar(right16.view(), left16.view(), lidar).looksSwapped());
}

TEST(PairOrientation, WithoutLidarTheBestMatchesSayIt) {
  const test::SyntheticStereo s = test::makeStereo(kWidth, kHeight, plane);
  const PairOrientation given = pairOrientationFromStereo(s.left.view(), s.right.view(), 0, 32);
  EXPECT_FALSE(given.fromLidar);
  EXPECT_GT(given.tested, 10u);
  EXPECT_FALSE(given.looksSwapped()) << given.describe();
  const PairOrientation swapped = pairOrientationFromStereo(s.right.view(), s.left.view(), 0, 32);
  EXPECT_TRUE(swapped.looksSwapped()) << swapped.describe();
  EXPECT_NE(swapped.describe().find("textured pixels"), std::string::npos) << swapped.describe();
}

TEST(PairOrientation, TooFewTexturedPatchesProveNothing) {
  const Image<std::uint8_t> flat(kWidth, kHeight, 128);
  const test::SyntheticStereo s = test::makeStereo(kWidth, kHeight, plane);
  EXPECT_FALSE(pairOrientationFromLidar(flat.view(), flat.view(), lidarOf(s)).looksSwapped());
  EXPECT_EQ(pairOrientationFromLidar(flat.view(), flat.view(), lidarOf(s)).tested, 0u);
  EXPECT_FALSE(pairOrientationFromStereo(flat.view(), flat.view(), 0, 32).looksSwapped());
  // Three LiDAR points decide nothing, however they vote.
  std::vector<LidarSample> few = lidarOf(s);
  few.resize(3);
  EXPECT_FALSE(pairOrientationFromLidar(s.right.view(), s.left.view(), few).looksSwapped());
  // Mismatched or missing images are the Densifier's to report, not this check's.
  EXPECT_EQ(pairOrientationFromLidar(s.left.view(), GrayImageView(), lidarOf(s)).tested, 0u);
}

geometry::StereoCalibration rig() {
  geometry::StereoCalibration c = test::smallRig();
  c.width = kWidth;
  c.height = kHeight;
  c.K << 100, 0, 100, 0, 100, 40, 0, 0, 1;
  return c;
}

std::vector<Eigen::Vector3f> scanOf(const geometry::StereoCalibration& c) {
  std::vector<Eigen::Vector3f> points;
  for (int v = 8; v < kHeight - 8; v += 4) {
    for (int u = 1; u < kWidth; u += 2) points.push_back(test::lidarPointAt(c, u, v, c.focalBaseline() / plane(u, v)));
  }
  return points;
}

TEST(PairOrientation, TheDensifierRefusesASwappedPairUnlessTheCheckIsOff) {
  const geometry::StereoCalibration c = rig();
  const test::SyntheticStereo s = test::makeStereo(kWidth, kHeight, plane);
  Densifier densifier;
  densifier.setCalibration(c);
  densifier.setStereoPair(s.left.view(), s.right.view());
  densifier.run(scanOf(c));
  EXPECT_EQ(densifier.lastMode(), MatchMode::Fused);
  EXPECT_FALSE(densifier.pairOrientation().looksSwapped());
  EXPECT_GT(densifier.pairOrientation().tested, 0u);

  densifier.setStereoPair(s.right.view(), s.left.view());
  try {
    densifier.run(scanOf(c));
    FAIL() << "a swapped pair was matched";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    for (const char* words : {"looks swapped", "LiDAR points", "wrong way round", "-no_pair_check"}) {
      EXPECT_NE(message.find(words), std::string::npos) << words << " in: " << message;
    }
  }
  // Stereo-only: the same refusal from the pair alone.
  EXPECT_THROW(densifier.runProjected(nullptr), std::invalid_argument);
  densifier.setPairCheck(false);
  EXPECT_NO_THROW(densifier.run(scanOf(c)));
  EXPECT_EQ(densifier.lastMode(), MatchMode::Fused);
  EXPECT_EQ(densifier.pairOrientation().tested, 0u) << "the check did not run";
}

}  // namespace
}  // namespace lidar_sgm
