// The LiDAR consistency check (lidar_consistency.hpp): a point whose disparity the textured pair
// contradicts is left out, points the pair agrees with are kept, and the Densifier applies it only
// when asked.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/lidar_consistency.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 200;
constexpr int kHeight = 60;
constexpr double kDisparity = 20.0;

test::SyntheticStereo plane() {
  return test::makeStereo(kWidth, kHeight, [](double, double) { return kDisparity; });
}

TEST(LidarConsistency, AContradictedPointIsDroppedAndAgreeingOnesAreKept) {
  const test::SyntheticStereo s = plane();
  LidarConsistencyOptions options;
  options.enabled = true;
  std::vector<LidarSample> samples;
  for (int x = 60; x < 180; x += 10) samples.push_back({x, 30, static_cast<int>(kDisparity * 16)});
  // A "moving object" point: 12 px off where the textured pair clearly matches.
  samples.push_back({105, 35, static_cast<int>((kDisparity + 12.0) * 16)});
  const std::size_t agreeing = samples.size() - 1;
  const std::size_t dropped = dropInconsistentLidar(s.left.view(), s.right.view(), samples, options);
  EXPECT_EQ(dropped, 1u);
  ASSERT_EQ(samples.size(), agreeing);
  for (const LidarSample& p : samples) EXPECT_EQ(p.disparity16, static_cast<int>(kDisparity * 16));
  // Off, nothing is dropped.
  samples.push_back({105, 35, static_cast<int>((kDisparity + 12.0) * 16)});
  options.enabled = false;
  EXPECT_EQ(dropInconsistentLidar(s.left.view(), s.right.view(), samples, options), 0u);
}

TEST(LidarConsistency, PointsNearTheBorderOrOnFlatPatchesAreKept) {
  const test::SyntheticStereo s = plane();
  Image<std::uint8_t> flat(kWidth, kHeight, 128);
  LidarConsistencyOptions options;
  options.enabled = true;
  std::vector<LidarSample> samples{{105, 30, static_cast<int>(40 * 16)}, {2, 30, 40 * 16}, {105, 1, 40 * 16}};
  EXPECT_EQ(dropInconsistentLidar(flat.view(), flat.view(), samples, options), 0u);  // no texture: no witness
  samples = {{2, 30, 40 * 16}, {105, 1, 40 * 16}, {21, 30, 40 * 16}};  // patches leave the images
  EXPECT_EQ(dropInconsistentLidar(s.left.view(), s.right.view(), samples, options), 0u);
}

TEST(LidarConsistency, ImpossibleOptionsAreNamed) {
  LidarConsistencyOptions options;
  options.costRatio = 0.5;
  EXPECT_THROW(validate(options), std::invalid_argument);
  options = {};
  options.searchRadius = 1;
  EXPECT_THROW(validate(options), std::invalid_argument);
  DensifierConfig config;
  config.lidarConsistency.minDisagreement = 0.0;
  try {
    validate(config);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("minDisagreement"), std::string::npos) << e.what();
  }
}

TEST(LidarConsistency, TheDensifierLeavesContradictedPointsOutOnlyWhenAsked) {
  const test::SyntheticStereo s = plane();
  std::vector<LidarSample> samples;
  // A block of wrong points, as a car that moved between the scan and the exposure, in a scan of
  // right ones.
  const auto inBlock = [](int x, int y) { return x >= 100 && x < 130 && y >= 20 && y < 40; };
  for (int y = 4; y < kHeight - 4; y += 2) {
    for (int x = 40; x < kWidth - 4; ++x) {
      const double d = inBlock(x, y) ? kDisparity + 10.0 : kDisparity;
      samples.push_back({x, y, static_cast<int>(d * 16)});
    }
  }
  const LidarPoints lidar(kWidth, kHeight, samples);
  // Pixels of the block without a right disparity (wrong, or dropped by the filters as doubtful).
  const auto wrongPixels = [&](bool consistency) {
    Densifier densifier;
    DensifierConfig config;
    config.computeCloud = false;
    config.matcher.numDisparities = 48;
    config.rangeMode = DisparityRangeMode::Fixed;
    config.lidarConsistency.enabled = consistency;
    densifier.setConfig(config);
    densifier.setStereoPair(s.left.view(), s.right.view());
    densifier.runProjected(&lidar);
    EXPECT_EQ(densifier.filterStats().inconsistentLidar > 0, consistency);
    int wrong = 0;
    for (int y = 20; y < 40; ++y) {
      for (int x = 100; x < 130; ++x) {
        const std::int16_t d = densifier.disparity()(x, y);
        wrong += d == kInvalidDisparity || std::abs(d / 16.0 - kDisparity) > 3.0 ? 1 : 0;
      }
    }
    return wrong;
  };
  const int without = wrongPixels(false);
  const int with = wrongPixels(true);
  EXPECT_GT(without, 100);
  EXPECT_LT(with, without / 4);
}

}  // namespace
}  // namespace lidar_sgm
