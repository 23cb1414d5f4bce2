#include <gtest/gtest.h>

#include <cmath>

#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/simulated_lidar.hpp"

namespace lidar_sgm {
namespace {

// Five GT pixels, worked out by hand:
//  gt 10, est 10.5   -> error 0.5: correct
//  gt 40, est 43.5   -> error 3.5 > 3 and > 5 % of 40 = 2: D1, not correct
//  gt 100, est 104   -> error 4 < 5: correct (by the 5 % rule), not D1
//  gt 20, est 30     -> error 10: D1
//  gt 30, no estimate -> D1, not dense
//  one pixel without GT (0) and one excluded pixel are not scored.
TEST(Metrics, AgreeWithAHandWorkedExample) {
  const int w = 7;
  const float gtValues[w] = {10.0f, 40.0f, 100.0f, 20.0f, 30.0f, 0.0f, 50.0f};
  const std::int16_t estValues[w] = {168, 43 * 16 + 8, 104 * 16, 30 * 16, kInvalidDisparity, 5 * 16, 0};
  const std::uint8_t excludeValues[w] = {0, 0, 0, 0, 0, 0, 1};
  const eval::DisparityMetrics m = eval::evaluateDisparity(ImageView<const std::int16_t>(estValues, w, 1),
                                                           ImageView<const float>(gtValues, w, 1),
                                                           ImageView<const std::uint8_t>(excludeValues, w, 1));
  EXPECT_EQ(m.gtPixels, 5);
  EXPECT_EQ(m.estimatedPixels, 4);
  EXPECT_DOUBLE_EQ(m.correct, 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(m.rmse, std::sqrt((0.5 * 0.5 + 4.0 * 4.0) / 2.0));
  EXPECT_DOUBLE_EQ(m.d1, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(m.d1Est, 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(m.density, 4.0 / 5.0);
}

TEST(Metrics, RejectsMismatchedSizes) {
  const float gt[2] = {1, 2};
  const std::int16_t est[3] = {1, 2, 3};
  EXPECT_THROW(eval::evaluateDisparity(ImageView<const std::int16_t>(est, 3, 1), ImageView<const float>(gt, 2, 1)),
               std::invalid_argument);
}

// The same five GT pixels split by an object map (the paper's Table II): pixels 2 and 4 (gt 40
// and 20, both wrong) are foreground; the last two pixels have no GT. Background: 10 (right) and
// 100 (right) estimated, 30 missing; foreground: 40 and 20 estimated, both wrong.
TEST(Metrics, ObjectSplitCountsWrongPixelsAmongTheEstimatedOnesPerSide) {
  const int w = 7;
  const float gtValues[w] = {10.0f, 40.0f, 100.0f, 20.0f, 30.0f, 0.0f, 0.0f};
  const std::int16_t estValues[w] = {168, 43 * 16 + 8, 104 * 16, 30 * 16, kInvalidDisparity, 5 * 16, 0};
  const std::uint8_t objectValues[w] = {0, 3, 0, 1, 0, 2, 0};
  const eval::ObjectSplitMetrics m = eval::evaluateObjectSplit(ImageView<const std::int16_t>(estValues, w, 1),
                                                               ImageView<const float>(gtValues, w, 1),
                                                               ImageView<const std::uint8_t>(objectValues, w, 1));
  EXPECT_EQ(m.gtPixels, 5);
  EXPECT_EQ(m.foregroundPixels, 2);
  EXPECT_DOUBLE_EQ(m.background, 0.0);
  EXPECT_DOUBLE_EQ(m.foreground, 1.0);
  EXPECT_DOUBLE_EQ(m.total, 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(m.density, 4.0 / 5.0);
  EXPECT_EQ(m.estimatedBackground, 2);  // the counts behind the shares, for a sum over frames
  EXPECT_EQ(m.estimatedForeground, 2);
  EXPECT_EQ(m.wrongBackground, 0);
  EXPECT_EQ(m.wrongForeground, 2);
  const std::uint8_t small[2] = {0, 0};
  EXPECT_THROW(eval::evaluateObjectSplit(ImageView<const std::int16_t>(estValues, w, 1),
                                         ImageView<const float>(gtValues, w, 1), ImageView<const std::uint8_t>(small, 2, 1)),
               std::invalid_argument);
}

// KITTI geometry (f 721.5, c_y 172.9): the +2 deg beam hits row 172.9 - 721.5*tan(2 deg) = 147.7 -> 148;
// the beams below leave the 375-row image around -16.5 deg, so about 2/3 of the 64 beams land.
TEST(SimulatedLidar, BeamRowsFollowTheHdl64Geometry) {
  const std::vector<int> rows = eval::simulatedBeamRows(1242, 375, {});
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.front(), 148);
  EXPECT_LE(rows.back(), 374);
  EXPECT_GT(rows.size(), 35u);
  EXPECT_LT(rows.size(), 50u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GE(rows[i] - rows[i - 1], 4);  // 0.425 deg apart: >= 5 px near the horizon
    EXPECT_LE(rows[i] - rows[i - 1], 8);
  }
}

TEST(SimulatedLidar, SamplesEveryOtherGtPixelOnBeamRowsAndMarksThem) {
  Image<float> gt(1242, 375, 0.0f);
  for (int x = 0; x < 1242; ++x) gt(x, 148) = 30.0f;
  gt(10, 0) = 40.0f;  // above every beam: never sampled
  Image<std::uint8_t> mask;
  eval::SimulatedLidarOptions options;
  options.noiseSigma = 0.0;
  const LidarPoints points = eval::simulateLidarFromGroundTruth(gt.view(), options, mask);
  EXPECT_EQ(points.size(), 621u);
  EXPECT_EQ(points.count(0, 148), 1);
  EXPECT_EQ(points.count(1, 148), 0);
  EXPECT_EQ(*points.begin(2, 148), 30 * 16);
  EXPECT_EQ(mask(2, 148), 1);
  EXPECT_EQ(mask(3, 148), 0);
  EXPECT_EQ(mask(10, 0), 0);
}

}  // namespace
}  // namespace lidar_sgm
