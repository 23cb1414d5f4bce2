// Ring recovery of KITTI velodyne scans (src/eval/lidar_rings.hpp), for P2's ring hold-out.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/test_data.hpp"
#include "eval/lidar_rings.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A point at azimuth `azimuthDeg` and elevation `elevationDeg`, `range` m away.
Eigen::Vector3f polar(double azimuthDeg, double elevationDeg, double range) {
  const double a = azimuthDeg * kPi / 180.0;
  const double e = elevationDeg * kPi / 180.0;
  return Eigen::Vector3f(static_cast<float>(range * std::cos(e) * std::cos(a)),
                         static_cast<float>(range * std::cos(e) * std::sin(a)), static_cast<float>(range * std::sin(e)));
}

/// KITTI's layout: laser by laser (top first), each a revolution from azimuth 0 through 180
/// (atan2 wraps to -180 there) back to ~0.
std::vector<Eigen::Vector3f> handMadeScan(int rings, int pointsPerRing) {
  std::vector<Eigen::Vector3f> points;
  for (int r = 0; r < rings; ++r) {
    for (int i = 0; i < pointsPerRing; ++i) {
      const double azimuth = 2.0 + 356.0 * i / (pointsPerRing - 1);  // 2 .. 358 deg
      points.push_back(polar(azimuth, 1.0 - 2.0 * r, 10.0 + i));
    }
  }
  return points;
}

TEST(LidarRings, HandMadeScanOfThreeRings) {
  const std::vector<Eigen::Vector3f> points = handMadeScan(3, 10);
  RingRecoveryOptions options;
  options.minPointsPerRing = 5;
  const std::vector<int> rings = recoverRings(points, options);
  ASSERT_EQ(rings.size(), 30u);
  for (std::size_t i = 0; i < rings.size(); ++i) EXPECT_EQ(rings[i], static_cast<int>(i / 10)) << "point " << i;
  const RingStatistics s = ringStatistics(points, rings);
  EXPECT_EQ(s.rings, 3);
  EXPECT_EQ(s.monotonic, 1);
  EXPECT_NEAR(s.medianElevationDeg[0], 1.0, 1e-4);
  EXPECT_NEAR(s.medianElevationDeg[2], -3.0, 1e-4);
  EXPECT_NEAR(s.medianSpreadDeg, 0.0, 1e-4);
  EXPECT_NEAR(s.minGapDeg, 2.0, 1e-4);
}

TEST(LidarRings, TheRearWrapOfAtan2DoesNotSplitARing) {
  // Each ring crosses azimuth 180 (atan2: +180 -> -180) in its middle: still 3 rings.
  const std::vector<Eigen::Vector3f> points = handMadeScan(3, 10);
  RingRecoveryOptions options;
  options.minPointsPerRing = 5;
  const std::vector<int> rings = recoverRings(points, options);
  EXPECT_EQ(rings[4], 0);
  EXPECT_EQ(rings[5], 0);  // azimuth 200 deg = atan2 -160 deg
  EXPECT_EQ(rings.back(), 2);
}

TEST(LidarRings, TooShortRingsAndInvalidPointsDoNotStartRings) {
  std::vector<Eigen::Vector3f> points = handMadeScan(3, 10);
  // minPointsPerRing above the ring length: nothing splits.
  RingRecoveryOptions options;
  options.minPointsPerRing = 11;
  const std::vector<int> merged = recoverRings(points, options);
  EXPECT_EQ(merged.back(), 1);  // the second wrap comes 20 points after the start: allowed once
  options.minPointsPerRing = 21;
  EXPECT_EQ(recoverRings(points, options).back(), 0);
  // A NaN and a point on the z axis inherit the ring before them and do not break the order.
  points.insert(points.begin() + 15, Eigen::Vector3f(std::nanf(""), 0.0f, 0.0f));
  points.insert(points.begin() + 16, Eigen::Vector3f(0.0f, 0.0f, 1.0f));
  options.minPointsPerRing = 5;
  const std::vector<int> rings = recoverRings(points, options);
  EXPECT_EQ(rings[15], 1);
  EXPECT_EQ(rings[16], 1);
  EXPECT_EQ(rings.back(), 2);
  EXPECT_TRUE(recoverRings(std::vector<Eigen::Vector3f>{}, options).empty());
}

TEST(LidarRings, CloudOverloadMatchesThePointOverload) {
  const std::vector<Eigen::Vector3f> points = handMadeScan(3, 300);
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (const Eigen::Vector3f& p : points) {
    pcl::PointXYZI q;
    q.x = p.x();
    q.y = p.y();
    q.z = p.z();
    q.intensity = 0.5f;
    cloud.push_back(q);
  }
  EXPECT_EQ(recoverRings(cloud), recoverRings(points));
  EXPECT_EQ(recoverRings(cloud).back(), 2);  // 300 points per ring >= the default 200
}

struct RealScan {
  const char* id;
  std::size_t points;
};

class KittiScanRings : public ::testing::TestWithParam<RealScan> {};

TEST_P(KittiScanRings, SixtyFourRingsTopToBottom) {
  const std::string folder = "kitti_stereo_lidar_calib_nogt";
  if (!test::haveSharedData(folder)) GTEST_SKIP() << "no " << folder << " under " << test::sharedDataRoot();
  const std::string path = test::sharedDataRoot() + "/" + folder + "/velodyne/" + GetParam().id + ".bin";
  const pcl::PointCloud<pcl::PointXYZI> scan = io::readKittiBin(path);
  ASSERT_EQ(scan.size(), GetParam().points);
  const std::vector<int> rings = recoverRings(scan);
  const RingStatistics s = ringStatistics(toPoints(scan), rings);
  std::size_t smallest = scan.size();
  for (const std::size_t c : s.counts) smallest = std::min(smallest, c);
  std::printf("  %s: %d rings, %zu..%zu points per ring; median elevation %.2f (ring 0) .. %.2f deg (ring %d); "
              "per-ring elevation IQR median %.3f deg; ring step min %.3f, median %.3f deg\n",
              GetParam().id, s.rings, smallest, *std::max_element(s.counts.begin(), s.counts.end()),
              s.medianElevationDeg.front(), s.medianElevationDeg.back(), s.rings - 1, s.medianSpreadDeg, s.minGapDeg,
              s.medianGapDeg);
  EXPECT_EQ(s.rings, 64);
  EXPECT_EQ(s.monotonic, 1) << "KITTI stores the top laser first";
  EXPECT_GT(smallest, 500u);
  EXPECT_GT(s.medianElevationDeg.front(), 1.5);
  EXPECT_LT(s.medianElevationDeg.back(), -22.0);
  // Within a ring the elevation is nearly constant: its spread stays around one ring step.
  EXPECT_LT(s.medianSpreadDeg, 0.6);
  EXPECT_GT(s.minGapDeg, 0.1);
}

INSTANTIATE_TEST_SUITE_P(Kitti, KittiScanRings,
                         ::testing::Values(RealScan{"stereo_rcnn_demo", 103344},
                                           RealScan{"densedepthmap_0000000001", 116631}),
                         [](const ::testing::TestParamInfo<RealScan>& paramInfo) { return std::string(paramInfo.param.id); });

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
