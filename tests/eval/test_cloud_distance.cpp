// The 3D cloud-to-cloud score on clouds whose nearest neighbours are known exactly: a grid and
// the same grid moved by a known offset, points at known ranges, NaN points, bad inputs; and the
// kd-tree's distances against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/eval/cloud_distance.hpp"
#include "lidar_sgm/eval/cloud_distance_report.hpp"

namespace lidar_sgm {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using eval::CloudDistanceOptions;
using eval::CloudDistanceScore;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// A 6 x 5 grid of 1 m spacing in the plane z = `z` (x 0..5, y 0..4).
Cloud grid(float z, float dx = 0.0f) {
  Cloud cloud;
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 6; ++x) cloud.push_back(pcl::PointXYZ(static_cast<float>(x) + dx, static_cast<float>(y), z));
  }
  return cloud;
}

/// Points on the x axis at the given ranges.
Cloud onAxis(const std::vector<float>& ranges) {
  Cloud cloud;
  for (float r : ranges) cloud.push_back(pcl::PointXYZ(r, 0.0f, 0.0f));
  return cloud;
}

CloudDistanceOptions noBands(std::vector<double> taus) {
  CloudDistanceOptions options;
  options.taus = std::move(taus);
  options.bandEdges = {};
  return options;
}

std::string errorOf(const Cloud& cloud, const Cloud& reference, const CloudDistanceOptions& options) {
  try {
    eval::compareClouds(cloud, reference, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

// The grid moved by 0.25 m (exact in float) along z: every nearest neighbour is the same grid
// point, 0.25 m away, both ways. At tau 0.25 m every point counts (within tau is inclusive), at
// 0.2499 m none does.
TEST(CloudDistance, ShiftedGridFlipsExactlyAtTau) {
  const CloudDistanceScore s = eval::compareClouds(grid(5.25f), grid(5.0f), noBands({0.2499, 0.25, 1.0}));
  EXPECT_EQ(s.overall.points, 30);
  EXPECT_EQ(s.overall.referencePoints, 30);
  ASSERT_EQ(s.overall.scores.size(), 3u);
  const eval::CloudDistanceAtTau& below = s.overall.scores[0];
  EXPECT_EQ(below.tau, 0.2499);
  EXPECT_EQ(below.precisePoints, 0);
  EXPECT_EQ(below.coveredReferencePoints, 0);
  EXPECT_EQ(below.precision, 0.0);
  EXPECT_EQ(below.completeness, 0.0);
  EXPECT_EQ(below.fScore, 0.0);  // both 0: F is 0, not undefined
  for (std::size_t t : {1u, 2u}) {
    EXPECT_EQ(s.overall.scores[t].precisePoints, 30);
    EXPECT_EQ(s.overall.scores[t].precision, 1.0);
    EXPECT_EQ(s.overall.scores[t].completeness, 1.0);
    EXPECT_EQ(s.overall.scores[t].fScore, 1.0);
  }
  EXPECT_EQ(s.overall.meanDistance, 0.25);
  EXPECT_EQ(s.overall.medianDistance, 0.25);
  EXPECT_EQ(s.overall.meanReferenceDistance, 0.25);
  EXPECT_EQ(s.overall.medianReferenceDistance, 0.25);
  EXPECT_TRUE(s.bands.empty());
  EXPECT_EQ(s.skippedPoints, 0);
  EXPECT_EQ(s.unjudgedPoints, 0);
}

// Precision and completeness are not symmetric: a cloud that covers only the grid's first column
// (moved 0.25 m) is all precise but completes 5 of 30 reference points; the F-score is their
// harmonic mean. The far reference points' distances are exact too: column x is x - 0.25 m away.
TEST(CloudDistance, PartialCloudIsPreciseButIncomplete) {
  Cloud column;
  for (int y = 0; y < 5; ++y) column.push_back(pcl::PointXYZ(0.25f, static_cast<float>(y), 5.0f));
  const CloudDistanceScore s = eval::compareClouds(column, grid(5.0f), noBands({0.25}));
  const eval::CloudDistanceAtTau& at = s.overall.scores[0];
  EXPECT_EQ(at.precisePoints, 5);
  EXPECT_EQ(at.coveredReferencePoints, 5);
  EXPECT_EQ(at.precision, 1.0);
  EXPECT_DOUBLE_EQ(at.completeness, 5.0 / 30.0);
  EXPECT_DOUBLE_EQ(at.fScore, 2.0 * (5.0 / 30.0) / (1.0 + 5.0 / 30.0));
  // Reference distances per column: 0.25, 0.75, 1.75, 2.75, 3.75, 4.75 (5 each).
  EXPECT_DOUBLE_EQ(s.overall.meanReferenceDistance, (0.25 + 0.75 + 1.75 + 2.75 + 3.75 + 4.75) / 6.0);
  EXPECT_DOUBLE_EQ(s.overall.medianReferenceDistance, 0.5 * (1.75 + 2.75));  // even count: the middle two
  EXPECT_EQ(s.overall.medianDistance, 0.25);
}

// Points on the x axis (range = x) in the bands [0,10) [10,20) [20,40) [40,80); 90 m is in none
// but counts overall. The 10-20 m points are moved 0.5 m sideways in the cloud: that band alone
// loses its precision and completeness.
TEST(CloudDistance, BandsCountByRangeAndScoreApart) {
  const Cloud reference = onAxis({1, 5, 12, 15, 30, 50, 90});
  Cloud cloud = reference;
  cloud[2].y = 0.5f;
  cloud[3].y = 0.5f;
  CloudDistanceOptions options;
  options.taus = {0.1};
  const CloudDistanceScore s = eval::compareClouds(cloud, reference, options);
  ASSERT_EQ(s.bands.size(), 4u);
  const std::vector<long> counts{2, 2, 1, 1};
  const std::vector<double> shares{1.0, 0.0, 1.0, 1.0};
  for (std::size_t b = 0; b < 4; ++b) {
    EXPECT_EQ(s.bands[b].near, options.bandEdges[b]);
    EXPECT_EQ(s.bands[b].far, options.bandEdges[b + 1]);
    EXPECT_EQ(s.bands[b].points, counts[b]) << b;
    EXPECT_EQ(s.bands[b].referencePoints, counts[b]) << b;
    EXPECT_EQ(s.bands[b].scores[0].precision, shares[b]) << b;
    EXPECT_EQ(s.bands[b].scores[0].completeness, shares[b]) << b;
  }
  EXPECT_EQ(s.overall.points, 7);
  EXPECT_DOUBLE_EQ(s.overall.scores[0].precision, 5.0 / 7.0);
  EXPECT_DOUBLE_EQ(s.overall.scores[0].completeness, 5.0 / 7.0);
  EXPECT_DOUBLE_EQ(s.bands[1].meanDistance, 0.5);
  EXPECT_EQ(s.bands[0].meanDistance, 0.0);

  // The same points seen from 100 m down the axis: ranges 99, 95, 88, 85, 70, 50, 10.
  options.origin = Eigen::Vector3f(100.0f, 0.0f, 0.0f);
  const CloudDistanceScore moved = eval::compareClouds(cloud, reference, options);
  EXPECT_EQ(moved.bands[0].referencePoints, 0);
  EXPECT_EQ(moved.bands[1].referencePoints, 1);  // 10 m: an edge belongs to the band above it
  EXPECT_EQ(moved.bands[3].referencePoints, 2);  // 50 and 70 m
}

// A cloud point's band decides its precision band, a reference point's its completeness band,
// though their nearest neighbours lie across the edge; a band with no point of one kind has that
// share undefined (NaN), and so its F-score, never 0.
TEST(CloudDistance, EachSideCountsInItsOwnBandAndEmptySharesAreUndefined) {
  CloudDistanceOptions options;
  options.taus = {0.2};
  options.bandEdges = {0, 10, 20};
  const CloudDistanceScore s = eval::compareClouds(onAxis({9.95f}), onAxis({10.05f}), options);
  EXPECT_EQ(s.bands[0].points, 1);
  EXPECT_EQ(s.bands[0].referencePoints, 0);
  EXPECT_EQ(s.bands[0].scores[0].precision, 1.0);
  EXPECT_TRUE(std::isnan(s.bands[0].scores[0].completeness));
  EXPECT_TRUE(std::isnan(s.bands[0].scores[0].fScore));
  EXPECT_EQ(s.bands[1].points, 0);
  EXPECT_EQ(s.bands[1].referencePoints, 1);
  EXPECT_TRUE(std::isnan(s.bands[1].scores[0].precision));
  EXPECT_TRUE(std::isnan(s.bands[1].meanDistance));
  EXPECT_EQ(s.bands[1].scores[0].completeness, 1.0);
  EXPECT_EQ(s.overall.scores[0].fScore, 1.0);
  // In JSON, undefined is null.
  const nlohmann::json json = eval::cloudDistanceJson(s);
  EXPECT_TRUE(json.at("bands").at(0).at("taus").at(0).at("completeness").is_null());
  EXPECT_EQ(json.at("bands").at(0).at("taus").at(0).at("precision").get<double>(), 1.0);
  EXPECT_EQ(json.at("bands").at(1).at("near").get<double>(), 10.0);
}

// NaN (and infinite) points are skipped on both sides and counted; the figures are those of the
// finite points alone.
TEST(CloudDistance, NonFinitePointsAreSkippedAndCounted) {
  Cloud cloud = grid(5.25f);
  Cloud reference = grid(5.0f);
  cloud.push_back(pcl::PointXYZ(kNaN, kNaN, kNaN));
  cloud.push_back(pcl::PointXYZ(1.0f, std::numeric_limits<float>::infinity(), 5.0f));
  reference.push_back(pcl::PointXYZ(kNaN, 0.0f, 0.0f));
  cloud.is_dense = false;
  reference.is_dense = false;
  const CloudDistanceScore s = eval::compareClouds(cloud, reference, noBands({0.25}));
  EXPECT_EQ(s.skippedPoints, 2);
  EXPECT_EQ(s.skippedReferencePoints, 1);
  EXPECT_EQ(s.overall.points, 30);
  EXPECT_EQ(s.overall.referencePoints, 30);
  EXPECT_EQ(s.overall.scores[0].fScore, 1.0);
}

// Judged points: precision over them alone; every point still completes the reference.
TEST(CloudDistance, PrecisionOverTheJudgedPointsOnly) {
  Cloud cloud = grid(5.0f);
  cloud.push_back(pcl::PointXYZ(20.0f, 0.0f, 5.0f));  // far from the reference: imprecise
  const eval::ReferenceCloud reference(grid(5.0f));
  EXPECT_EQ(reference.size(), 30u);
  const CloudDistanceScore all = reference.score(cloud, noBands({0.1}));
  EXPECT_DOUBLE_EQ(all.overall.scores[0].precision, 30.0 / 31.0);
  std::vector<int> judged;
  for (int i = 0; i < 30; i += 2) judged.push_back(i);  // 15 grid points, not the far one
  const CloudDistanceScore some = reference.score(cloud, judged, noBands({0.1}));
  EXPECT_EQ(some.overall.points, 15);
  EXPECT_EQ(some.unjudgedPoints, 16);
  EXPECT_EQ(some.overall.scores[0].precision, 1.0);
  EXPECT_EQ(some.overall.scores[0].completeness, 1.0);  // the unjudged points complete it too
  EXPECT_THROW(reference.score(cloud, {31}, noBands({0.1})), std::invalid_argument);
  EXPECT_THROW(reference.score(cloud, {-1}, noBands({0.1})), std::invalid_argument);
}

// The kd-tree's nearest neighbours are exact: against brute force on random clouds, and the same
// for any number of threads.
TEST(CloudDistance, MatchesBruteForceForAnyThreadCount) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
  Cloud cloud, reference;
  for (int i = 0; i < 9000; ++i) cloud.push_back(pcl::PointXYZ(coordinate(random), coordinate(random), coordinate(random)));
  for (int i = 0; i < 700; ++i) {
    reference.push_back(pcl::PointXYZ(coordinate(random), coordinate(random), coordinate(random)));
  }
  CloudDistanceOptions options;
  options.taus = {0.5, 1.5};
  options.bandEdges = {0, 10, 20, 40};
  const CloudDistanceScore one = eval::compareClouds(cloud, reference, options);

  const auto nearest = [](const pcl::PointXYZ& p, const Cloud& other) {
    double best = std::numeric_limits<double>::infinity();
    for (const pcl::PointXYZ& q : other) {
      best = std::min(best, (p.getVector3fMap() - q.getVector3fMap()).cast<double>().norm());
    }
    return best;
  };
  double sum = 0.0;
  long precise = 0;
  for (const pcl::PointXYZ& p : cloud) {
    const double d = nearest(p, reference);
    sum += d;
    precise += d <= 1.5 ? 1 : 0;
  }
  long covered = 0;
  for (const pcl::PointXYZ& p : reference) covered += nearest(p, cloud) <= 1.5 ? 1 : 0;
  EXPECT_NEAR(one.overall.meanDistance, sum / 9000.0, 1e-6);
  EXPECT_EQ(one.overall.scores[1].precisePoints, precise);
  EXPECT_EQ(one.overall.scores[1].coveredReferencePoints, covered);

  for (int threads : {2, 3, 8}) {
    options.threads = threads;
    const CloudDistanceScore many = eval::compareClouds(cloud, reference, options);
    EXPECT_EQ(eval::cloudDistanceJson(many).dump(), eval::cloudDistanceJson(one).dump()) << threads;
  }
}

TEST(CloudDistance, BadInputsAreRefusedNamingTheProblem) {
  const Cloud g = grid(5.0f);
  const CloudDistanceOptions fine = noBands({0.1});
  EXPECT_NE(errorOf(Cloud(), g, fine).find("the cloud is empty"), std::string::npos);
  EXPECT_NE(errorOf(g, Cloud(), fine).find("the reference cloud is empty"), std::string::npos);
  Cloud nan;
  nan.push_back(pcl::PointXYZ(kNaN, kNaN, kNaN));
  EXPECT_NE(errorOf(nan, g, fine).find("the cloud has no finite point"), std::string::npos);
  EXPECT_NE(errorOf(g, nan, fine).find("the reference cloud has no finite point"), std::string::npos);
  for (double tau : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_NE(errorOf(g, g, noBands({0.1, tau})).find("tau"), std::string::npos) << tau;
  }
  EXPECT_NE(errorOf(g, g, noBands({})).find("no tau"), std::string::npos);
  CloudDistanceOptions bands = fine;
  bands.bandEdges = {0, 20, 10};
  EXPECT_NE(errorOf(g, g, bands).find("band edges must increase (10 after 20)"), std::string::npos);
  bands.bandEdges = {0, 10, 10};
  EXPECT_NE(errorOf(g, g, bands).find("must increase"), std::string::npos);
  bands.bandEdges = {10};
  EXPECT_NE(errorOf(g, g, bands).find("one band edge"), std::string::npos);
  bands.bandEdges = {-5, 10};
  EXPECT_NE(errorOf(g, g, bands).find("band edge -5"), std::string::npos);
  CloudDistanceOptions threads = fine;
  threads.threads = 0;
  EXPECT_NE(errorOf(g, g, threads).find("threads"), std::string::npos);
}

// Medians over frames leave out the frames where a share is not defined; counts are summed.
TEST(CloudDistance, MediansOverFramesSkipUndefinedShares) {
  CloudDistanceOptions options;
  options.taus = {0.2};
  options.bandEdges = {0, 10, 20};
  const CloudDistanceScore a = eval::compareClouds(onAxis({9.95f}), onAxis({10.05f}), options);  // band 0: C NaN
  const CloudDistanceScore b = eval::compareClouds(onAxis({1.0f, 2.0f}), onAxis({1.0f, 2.5f}), options);
  const CloudDistanceScore c = eval::compareClouds(onAxis({1.0f}), onAxis({1.0f}), options);
  const CloudDistanceScore m = eval::medianCloudDistance({a, b, c});
  EXPECT_EQ(m.overall.points, 4);
  EXPECT_EQ(m.bands[0].referencePoints, 3);
  // Band 0 completeness: b 0.5, c 1 (a undefined): median 0.75. Precision: a 1, b 0.5, c 1: 1.
  EXPECT_DOUBLE_EQ(m.bands[0].scores[0].completeness, 0.75);
  EXPECT_DOUBLE_EQ(m.bands[0].scores[0].precision, 1.0);
  // Band 1 has a reference point in a alone, no point anywhere: precision undefined in every frame.
  EXPECT_TRUE(std::isnan(m.bands[1].scores[0].precision));
  EXPECT_DOUBLE_EQ(m.bands[1].scores[0].completeness, 1.0);
  CloudDistanceOptions other = options;
  other.taus = {0.3};
  EXPECT_THROW(eval::medianCloudDistance({a, eval::compareClouds(onAxis({1.0f}), onAxis({1.0f}), other)}),
               std::invalid_argument);
  EXPECT_TRUE(eval::medianCloudDistance({}).bands.empty());
}

}  // namespace
}  // namespace lidar_sgm
