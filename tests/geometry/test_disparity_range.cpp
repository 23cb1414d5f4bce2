#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "lidar_sgm/geometry/disparity_range.hpp"

using lidar_sgm::LidarSample;
using lidar_sgm::Parameters;
using lidar_sgm::geometry::DisparityRange;
using lidar_sgm::geometry::DisparityRangeRule;
using lidar_sgm::geometry::disparityRangeFromLidar;

namespace {

/// `count` samples at disparity `px` (x16), spread over a 100-pixel-wide image.
void addSamples(std::vector<LidarSample>& samples, int count, double px) {
  for (int i = 0; i < count; ++i) {
    samples.push_back({i % 100, i / 100, static_cast<int>(px * 16.0 + 0.5)});
  }
}

/// A far street: 20000 points spread over 2..40 px.
std::vector<LidarSample> farScene() {
  std::vector<LidarSample> samples;
  for (int i = 0; i < 20000; ++i) samples.push_back({i % 100, i / 100, 32 + (i * 7) % (38 * 16)});
  return samples;
}

}  // namespace

TEST(DisparityRange, EmptyScanKeepsTheFixedRange) {
  Parameters fixed;
  fixed.minDisparity = -16;
  fixed.numDisparities = 96;
  const DisparityRange r = disparityRangeFromLidar({}, fixed);
  EXPECT_FALSE(r.fromLidar);
  EXPECT_EQ(r.minDisparity, -16);
  EXPECT_EQ(r.numDisparities, 96);
  EXPECT_EQ(r.points, 0u);
  EXPECT_EQ(r.describe(), "[-16, 80) px (fixed)");
}

TEST(DisparityRange, RuleWorkedByHandOnAFarScene) {
  // dMax = 39.9 px (the 11th largest of 20000, all within 2..40 px); margin max(8, 2.0) = 8;
  // top 47.9 -> 48 with the floor of 16.
  const DisparityRange r = disparityRangeFromLidar(farScene(), Parameters{});
  EXPECT_TRUE(r.fromLidar);
  EXPECT_EQ(r.minDisparity, 0);
  EXPECT_NEAR(r.lidarMax, 40.0, 0.2);
  EXPECT_EQ(r.numDisparities, 48);
  EXPECT_EQ(r.points, 20000u);
}

TEST(DisparityRange, NearClusterCounts) {
  // A parked car: 300 points at 163.4 px among the far street. Margin 5 % = 8.17 px -> 171.6 -> 176.
  std::vector<LidarSample> samples = farScene();
  addSamples(samples, 300, 163.4);
  const DisparityRange r = disparityRangeFromLidar(samples, Parameters{});
  EXPECT_NEAR(r.lidarMax, 163.4, 1.0 / 16);
  EXPECT_EQ(r.numDisparities, 176);
  EXPECT_FALSE(r.capped);
  EXPECT_EQ(r.describe(), "[0, 176) px from the LiDAR (max 163.4 px)");
}

TEST(DisparityRange, HandfulOfStraysIgnored) {
  std::vector<LidarSample> samples = farScene();
  addSamples(samples, 10, 400.0);  // returns from the ego vehicle, rain drops
  const DisparityRange r = disparityRangeFromLidar(samples, Parameters{});
  EXPECT_LT(r.lidarMax, 40.0);
  EXPECT_EQ(r.numDisparities, 48);
  // One more than the rule sets aside: then they count (and hit the cap).
  addSamples(samples, 1, 400.0);
  const DisparityRange all = disparityRangeFromLidar(samples, Parameters{});
  EXPECT_NEAR(all.lidarMax, 400.0, 0.1);
  EXPECT_EQ(all.numDisparities, 256);
  EXPECT_TRUE(all.capped);
}

TEST(DisparityRange, SparseScanSetsAsideAtMostItsFraction) {
  // 50 points: 1 % of them is 0 points, so even the single largest counts.
  std::vector<LidarSample> samples;
  addSamples(samples, 49, 10.0);
  addSamples(samples, 1, 100.0);
  EXPECT_NEAR(disparityRangeFromLidar(samples, Parameters{}).lidarMax, 100.0, 0.1);
}

TEST(DisparityRange, GranularityAtHalfScale) {
  std::vector<LidarSample> samples = farScene();
  addSamples(samples, 300, 163.4);
  Parameters half;
  half.scale = 0.5f;
  const DisparityRange r = disparityRangeFromLidar(samples, half);
  EXPECT_EQ(r.numDisparities, 192);  // 171.6 rounded up to a multiple of 32
  EXPECT_EQ(r.minDisparity % 2, 0);
  Parameters matched = half;
  matched.numDisparities = r.numDisparities;
  matched.minDisparity = r.minDisparity;
  EXPECT_EQ(lidar_sgm::validationError(matched), "");
  // The far scene: 48 -> 64 at half scale.
  EXPECT_EQ(disparityRangeFromLidar(farScene(), half).numDisparities, 64);
}

TEST(DisparityRange, CapAndFloor) {
  std::vector<LidarSample> samples = farScene();
  addSamples(samples, 300, 300.0);
  DisparityRangeRule rule;
  EXPECT_EQ(disparityRangeFromLidar(samples, Parameters{}, rule).numDisparities, 256);
  rule.maxNumDisparities = 192;
  const DisparityRange capped = disparityRangeFromLidar(samples, Parameters{}, rule);
  EXPECT_EQ(capped.numDisparities, 192);
  EXPECT_TRUE(capped.capped);
  EXPECT_EQ(capped.describe(), "[0, 192) px from the LiDAR (max 300.0 px, capped)");
  rule.maxNumDisparities = 256;
  rule.minNumDisparities = 128;
  EXPECT_EQ(disparityRangeFromLidar(farScene(), Parameters{}, rule).numDisparities, 128);
}

TEST(DisparityRange, InvalidRuleNamesTheField) {
  DisparityRangeRule rule;
  rule.maxNumDisparities = 100;
  try {
    disparityRangeFromLidar(farScene(), Parameters{}, rule);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("maxNumDisparities"), std::string::npos) << e.what();
  }
  rule = DisparityRangeRule{};
  rule.minNumDisparities = 512;  // above the cap
  EXPECT_THROW(disparityRangeFromLidar(farScene(), Parameters{}, rule), std::invalid_argument);
  rule = DisparityRangeRule{};
  rule.ignoredFraction = -0.1;
  EXPECT_THROW(disparityRangeFromLidar({}, Parameters{}, rule), std::invalid_argument);
}
