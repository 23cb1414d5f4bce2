// lidar_sgm_batch -map's pieces: the voxel map's accumulation and the picture from above.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "apps/map_pieces_fixture.hpp"
#include "batch/map_picture.hpp"
#include "lidar_sgm/sequence/voxel_map.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

// --- the voxel map ----------------------------------------------------------------------------

PointXYZRGBConfidence point(float x, float y, float z, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
                            float confidence = 0.0f) {
  PointXYZRGBConfidence p;
  p.x = x;
  p.y = y;
  p.z = z;
  p.rgba = 0xff000000u;
  p.r = r;
  p.g = g;
  p.b = b;
  p.confidence = confidence;
  return p;
}

sequence::MapInput input(std::vector<PointXYZRGBConfidence> points, bool color = true, bool confidence = true) {
  sequence::MapInput in;
  for (const PointXYZRGBConfidence& p : points) in.points.push_back(p);
  in.hasColor = color;
  in.hasConfidence = confidence;
  return in;
}

TEST_F(MapPieces, AVoxelKeepsTheCentroidMeanColorAndMeanConfidenceOfItsPoints) {
  sequence::VoxelMap map(1.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  map.add(input({point(0.2f, 0.2f, 0.2f, 10, 20, 30, 0.2f), point(-0.5f, 0.0f, 0.0f, 1, 2, 3, 1.0f),
                 point(nan, 0, 0), point(0.6f, 0.4f, 0.8f, 20, 40, 61, 0.6f)}),
          Eigen::Isometry3d::Identity());
  ASSERT_EQ(map.size(), 2u) << "(-0.5, 0, 0) is in voxel -1, not 0; NaN points are skipped";
  EXPECT_TRUE(map.hasColor());
  EXPECT_TRUE(map.hasConfidence());
  const pcl::PointCloud<PointXYZRGBConfidence> points = map.points();
  EXPECT_NEAR(points[0].x, 0.4f, 1e-6);
  EXPECT_NEAR(points[0].y, 0.3f, 1e-6);
  EXPECT_NEAR(points[0].z, 0.5f, 1e-6);
  EXPECT_EQ(points[0].r, 15);
  EXPECT_EQ(points[0].g, 30);
  EXPECT_EQ(points[0].b, 46) << "45.5 rounds up";
  EXPECT_NEAR(points[0].confidence, 0.4f, 1e-6);
  EXPECT_EQ(points[1].x, -0.5f);
  EXPECT_EQ(points[1].r, 1);

  // The clouds' transform: shifted by 10 m in x, the same points land in new voxels.
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = Eigen::Vector3d(10, 0, 0);
  map.add(input({point(0.2f, 0.2f, 0.2f)}), shift);
  ASSERT_EQ(map.size(), 3u);
  EXPECT_NEAR(map.points()[2].x, 10.2f, 1e-5);
}

TEST_F(MapPieces, FieldsAreKeptOnlyWhenEveryCloudHasThem) {
  sequence::VoxelMap map(0.1);
  EXPECT_FALSE(map.hasColor()) << "an empty map has nothing";
  map.add(input({point(0, 0, 0, 9, 9, 9, 0.5f)}), Eigen::Isometry3d::Identity());
  map.add(input({point(1, 0, 0)}, false, true), Eigen::Isometry3d::Identity());
  EXPECT_FALSE(map.hasColor());
  EXPECT_TRUE(map.hasConfidence());
  EXPECT_EQ(map.points()[0].r, 0) << "no color when the map has none";
}

TEST_F(MapPieces, TheSameCloudsInTheSameOrderGiveTheSameMapBitForBitAndOrderOnlyMovesVoxels) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
  std::vector<sequence::MapInput> clouds(3);
  for (sequence::MapInput& cloud : clouds) {
    cloud.hasColor = cloud.hasConfidence = true;
    for (int i = 0; i < 5000; ++i) {
      cloud.points.push_back(point(coordinate(random), coordinate(random) / 10, coordinate(random),
                                   static_cast<std::uint8_t>(random() % 256), 7, 9, 0.5f));
    }
  }
  const auto build = [&](const std::vector<int>& order) {
    sequence::VoxelMap map(0.5);
    for (int i : order) map.add(clouds[static_cast<std::size_t>(i)], Eigen::Isometry3d::Identity());
    return map.points();
  };
  const pcl::PointCloud<PointXYZRGBConfidence> a = build({0, 1, 2});
  const pcl::PointCloud<PointXYZRGBConfidence> b = build({0, 1, 2});
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(PointXYZRGBConfidence)), 0);

  // Another order: the voxels of the first cloud come first; the same voxels, the same means.
  const pcl::PointCloud<PointXYZRGBConfidence> c = build({2, 1, 0});
  ASSERT_EQ(c.size(), a.size());
  EXPECT_LT(std::abs(c[0].x - clouds[2].points[0].x), 0.5f) << "first voxel: the first cloud's first point";
  const auto sorted = [](const pcl::PointCloud<PointXYZRGBConfidence>& m) {
    std::vector<std::array<float, 4>> v;
    for (const PointXYZRGBConfidence& p : m) v.push_back({p.x, p.y, p.z, static_cast<float>(p.r)});
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<std::array<float, 4>> sa = sorted(a);
  const std::vector<std::array<float, 4>> sc = sorted(c);
  for (std::size_t i = 0; i < sa.size(); ++i) {
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(sa[i][k], sc[i][k], 1e-5) << i;
    ASSERT_EQ(sa[i][3], sc[i][3]) << i;
  }
}

TEST_F(MapPieces, AKilometreLongDriveKeepsEveryVoxelApart) {
  // pcl::VoxelGrid numbers a box's voxels in 32 bits: 2 km x 2 km x 50 m at 0.1 m is 2e11 voxels,
  // which it refuses. Here two points 0.1 m apart at the far corner stay two voxels.
  sequence::VoxelMap map(0.1);
  map.add(input({point(0, 0, 0), point(2000.05f, 50.05f, 2000.05f), point(2000.15f, 50.05f, 2000.05f)}),
          Eigen::Isometry3d::Identity());
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map.points()[2].x, 2000.15f);
  EXPECT_NE(errorOf([] { sequence::VoxelMap(0.0); }).find("voxel size must be positive"), std::string::npos);
  EXPECT_NE(errorOf([] { sequence::VoxelMap(-1.0); }).find("voxel size must be positive"), std::string::npos);
  sequence::VoxelMap tiny(1e-9);
  EXPECT_NE(errorOf([&] { tiny.add(input({point(1e9f, 0, 0)}), Eigen::Isometry3d::Identity()); }).find("too far out"),
            std::string::npos);
}

// --- the picture from above -------------------------------------------------------------------

TEST_F(MapPieces, TopViewShowsEachPixelsHighestPointForwardUpWithTheTrajectory) {
  pcl::PointCloud<PointXYZRGBConfidence> map;
  map.push_back(point(0.05f, 0.0f, 10.05f, 255, 0, 0));   // ground, red
  map.push_back(point(0.05f, -2.0f, 10.05f, 0, 255, 0));  // 2 m up (y down), green: on top
  map.push_back(point(0.05f, -2.0f, 10.05f, 0, 0, 255));  // as high, later: the first stays
  map.push_back(point(5.05f, 0.0f, 0.05f, 0, 0, 255));    // nearer, right: lower in the picture
  TopViewOptions options;
  options.minMetresPerPixel = 0.1;
  options.margin = 3;
  const std::vector<Eigen::Vector3d> trajectory{{0.05, 0, 0.05}, {0.05, 0, 2.05}};
  const TopView view = renderTopView(map, true, trajectory, options);
  EXPECT_DOUBLE_EQ(view.metresPerPixel, 0.1);
  ASSERT_EQ(view.image.type(), CV_8UC3);
  EXPECT_EQ(view.image.cols, 3 + 51 + 3);  // x 0.05 .. 5.05 m
  EXPECT_EQ(view.image.rows, 3 + 101 + 3);  // z 0.05 .. 10.05 m
  EXPECT_EQ(view.image.at<cv::Vec3b>(3, 3), cv::Vec3b(0, 255, 0)) << "far (z = 10) is at the top";
  EXPECT_EQ(view.image.at<cv::Vec3b>(3 + 100, 3 + 50), cv::Vec3b(255, 0, 0)) << "BGR blue, near right";
  EXPECT_EQ(view.image.at<cv::Vec3b>(3 + 90, 3), cv::Vec3b(255, 255, 255)) << "the trajectory, 1 m ahead";
  EXPECT_EQ(view.image.at<cv::Vec3b>(3 + 50, 3 + 25), cv::Vec3b(0, 0, 0)) << "background";

  // Without colors: turbo of the height, the top point at the map's highest color.
  const TopView heights = renderTopView(map, false, {}, options);
  EXPECT_NE(heights.image.at<cv::Vec3b>(3, 3), heights.image.at<cv::Vec3b>(3 + 100, 3 + 50));
  const TopView again = renderTopView(map, false, {}, options);
  EXPECT_EQ(cv::norm(heights.image, again.image, cv::NORM_INF), 0.0);

  // A 5 km drive: the long side is capped, the scale grows.
  map.push_back(point(0.0f, 0.0f, 5000.0f));
  const TopView far = renderTopView(map, true, {}, TopViewOptions{});
  EXPECT_LE(far.image.rows, 2000);
  EXPECT_GE(far.image.rows, 1999) << "the long side fills the picture";
  EXPECT_LE(far.image.cols, 2000);
  EXPECT_GT(far.metresPerPixel, 2.5);
  EXPECT_NE(errorOf([] { renderTopView({}, true, {}); }).find("no point"), std::string::npos);
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
