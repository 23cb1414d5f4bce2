#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "lidar_sgm/eval/cloud_metrics.hpp"

namespace lidar_sgm {
namespace {

// f*b = 480 px*m: GT disparity 12 px is 40 m, and an x16 estimate k is z = 480 * 16 / k.
constexpr double kFocalBaseline = 480.0;

struct Row {
  std::vector<std::int16_t> estimate;
  std::vector<float> groundTruth;
  std::vector<std::uint8_t> exclude;

  ImageView<const std::int16_t> e() const { return {estimate.data(), static_cast<int>(estimate.size()), 1}; }
  ImageView<const float> g() const { return {groundTruth.data(), static_cast<int>(groundTruth.size()), 1}; }
  ImageView<const std::uint8_t> x() const {
    if (exclude.empty()) return {};
    return {exclude.data(), static_cast<int>(exclude.size()), 1};
  }
  eval::CloudMetrics cloud(bool dense, double focalBaseline = kFocalBaseline) const {
    eval::CloudScoring scoring;
    scoring.denseGroundTruth = dense;
    return eval::evaluateCloud(e(), g(), x(), focalBaseline, scoring);
  }
  eval::DepthMetrics depth() const { return eval::evaluateDepth(e(), g(), x(), kFocalBaseline); }
};

std::int16_t x16(double disparity) { return static_cast<std::int16_t>(std::lround(disparity * kDisparityScale)); }

// 40 m, 20 m, 10 m and exactly 80 m (the max depth is inclusive), all estimated exactly.
TEST(CloudMetrics, PerfectEstimateScoresOne) {
  const Row row{{x16(12), x16(24), x16(48), x16(6)}, {12, 24, 48, 6}, {}};
  for (bool dense : {false, true}) {
    const eval::CloudMetrics m = row.cloud(dense);
    EXPECT_EQ(m.points, 4);
    EXPECT_EQ(m.gtPixels, 4);
    for (const eval::CloudScore& s : {m.tau3, m.tau5}) {
      EXPECT_DOUBLE_EQ(s.precision, 1.0);
      EXPECT_DOUBLE_EQ(s.completeness, 1.0);
      EXPECT_DOUBLE_EQ(s.fScore, 1.0);
    }
  }
  const eval::DepthMetrics d = row.depth();
  EXPECT_EQ(d.gtPixels, 4);
  EXPECT_EQ(d.estimatedPixels, 4);
  EXPECT_DOUBLE_EQ(d.rmseMm, 0.0);
  EXPECT_DOUBLE_EQ(d.maeMm, 0.0);
  EXPECT_DOUBLE_EQ(d.irmsePerKm, 0.0);
  EXPECT_DOUBLE_EQ(d.imaePerKm, 0.0);
  EXPECT_DOUBLE_EQ(d.density, 1.0);
}

// Every estimate is 40 m; the GT is moved across each tolerance edge by 0.01 px of disparity:
//  GT 12.59 px = 38.125 m: error 1.875 m <= 5 % (1.906 m), > 3 % (1.144 m)
//  GT 12.61 px = 38.065 m: error 1.935 m >  5 % (1.903 m)
//  GT 12.35 px = 38.866 m: error 1.134 m <= 3 % (1.166 m)
//  GT 12.37 px = 38.804 m: error 1.196 m >  3 % (1.164 m), <= 5 %
TEST(CloudMetrics, ToleranceEdgeIsTauTimesGtDepth) {
  const Row row{{x16(12), x16(12), x16(12), x16(12)}, {12.59f, 12.61f, 12.35f, 12.37f}, {}};
  const eval::CloudMetrics m = row.cloud(false);
  EXPECT_EQ(m.points, 4);
  EXPECT_DOUBLE_EQ(m.tau5.precision, 3.0 / 4.0);     // all but GT 12.61
  EXPECT_DOUBLE_EQ(m.tau3.precision, 1.0 / 4.0);     // GT 12.35 only
  EXPECT_DOUBLE_EQ(m.tau5.completeness, 3.0 / 4.0);  // every GT pixel is within 80 m and has a point
  EXPECT_DOUBLE_EQ(m.tau5.fScore, 3.0 / 4.0);
}

// Near the camera the 0.1 m floor decides: f*b = 16, GT 16 px = 1 m (5 % would be 0.05 m).
// Estimate 233/16 px = 1.0987 m (error 0.0987 m: correct), 232/16 px = 1.1034 m (0.1034 m: wrong).
TEST(CloudMetrics, ToleranceNeverBelowTenCentimetres) {
  const Row row{{233, 232}, {16, 16}, {}};
  const eval::CloudMetrics m = row.cloud(false, 16.0);
  EXPECT_DOUBLE_EQ(m.tau5.precision, 0.5);
  EXPECT_DOUBLE_EQ(m.tau3.precision, 0.5);
}

// A correct point at 40 m and a point at 80 m where the GT is 0. With dense GT (P3) the 0 is sky
// and the point is wrong; with sparse GT it is unknown and not scored. Completeness is the same.
TEST(CloudMetrics, SkyPointsAreWrongOnlyInDenseGroundTruth) {
  const Row row{{x16(12), x16(6)}, {12, 0}, {}};
  const eval::CloudMetrics dense = row.cloud(true);
  EXPECT_EQ(dense.points, 2);
  EXPECT_DOUBLE_EQ(dense.tau5.precision, 0.5);
  EXPECT_DOUBLE_EQ(dense.tau5.completeness, 1.0);
  EXPECT_DOUBLE_EQ(dense.tau5.fScore, 2.0 * 0.5 * 1.0 / 1.5);
  const eval::CloudMetrics sparse = row.cloud(false);
  EXPECT_EQ(sparse.points, 1);
  EXPECT_DOUBLE_EQ(sparse.tau5.precision, 1.0);
  EXPECT_DOUBLE_EQ(sparse.tau5.fScore, 1.0);
}

// Pixel 0: estimate 95/16 px = 80.84 m, beyond 80 m: no point, although dense GT says sky there.
// Pixel 1: GT 5.9 px = 81.36 m is not asked for; the estimate 80 m is a point, correct (1.36 m < 5 %).
// Pixel 2: GT 40 m, estimate 80.84 m: no point, so the GT pixel is not covered.
// Pixel 3: a LiDAR input pixel with a wrong estimate: scored neither way.
TEST(CloudMetrics, PointsAndGroundTruthBeyondEightyMetresAreLeftOut) {
  const Row row{{95, x16(6), 95, x16(24)}, {0, 5.9f, 12, 12}, {0, 0, 0, 1}};
  const eval::CloudMetrics m = row.cloud(true);
  EXPECT_EQ(m.points, 1);
  EXPECT_EQ(m.gtPixels, 1);
  EXPECT_DOUBLE_EQ(m.tau5.precision, 1.0);
  EXPECT_DOUBLE_EQ(m.tau5.completeness, 0.0);
  EXPECT_DOUBLE_EQ(m.tau5.fScore, 0.0);
  const eval::DepthMetrics d = row.depth();
  EXPECT_EQ(d.gtPixels, 1);
  EXPECT_EQ(d.estimatedPixels, 0);
  EXPECT_DOUBLE_EQ(d.density, 0.0);
}

// GT 40 m estimated at 30 m (16 px): error 10 m = 10000 mm; inverse depth 1000/30 - 1000/40 =
// 8.333 1/km. GT 20 m estimated exactly. GT 10 m without estimate. An excluded pixel, wrong.
TEST(DepthMetrics, MillimetresAndInverseKilometres) {
  const Row row{{x16(16), x16(24), kInvalidDisparity, x16(40)}, {12, 24, 48, 12}, {0, 0, 0, 1}};
  const eval::DepthMetrics d = row.depth();
  EXPECT_EQ(d.gtPixels, 3);
  EXPECT_EQ(d.estimatedPixels, 2);
  EXPECT_DOUBLE_EQ(d.density, 2.0 / 3.0);
  EXPECT_NEAR(d.rmseMm, 10000.0 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(d.maeMm, 5000.0, 1e-9);
  const double inverseError = 1000.0 / 30.0 - 1000.0 / 40.0;  // 8.333 1/km
  EXPECT_NEAR(d.irmsePerKm, inverseError / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(d.imaePerKm, inverseError / 2.0, 1e-9);
}

TEST(CloudMetrics, RejectsMismatchedSizesAndNonPositiveFocalBaseline) {
  const Row wrongSize{{1, 2, 3}, {1, 2}, {}};
  EXPECT_THROW(wrongSize.cloud(false), std::invalid_argument);
  EXPECT_THROW(wrongSize.depth(), std::invalid_argument);
  const Row row{{16}, {1}, {}};
  EXPECT_THROW(row.cloud(false, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
