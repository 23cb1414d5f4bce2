// A sparse LiDAR image given as disparities that holds depths (or the other way round) is named:
// impossible values are an error, a depth-like name or row trend a warning; real KITTI LiDAR
// disparities pass, and the same scan written as a KITTI depth PNG is recognised.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "common/test_data.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/sparse_lidar_check.hpp"

namespace lidar_sgm {
namespace {

/// A road-like scan: rows 20..99, every 3rd column; disparity grows from 5 px at the top row to
/// 45 px at the bottom one (ground nearer at the bottom). `asDepth`: the values are depths F/d
/// (F = 380 px m) read as if they were disparities.
Image<std::int16_t> roadScan(bool asDepth) {
  Image<std::int16_t> image(300, 100, kInvalidDisparity);
  for (int y = 20; y < 100; ++y) {
    const double d = 5.0 + 40.0 * (y - 20) / 79.0;
    const double value = asDepth ? 380.0 / d : d;
    for (int x = 0; x < 300; x += 3) image(x, y) = static_cast<std::int16_t>(std::lround(value * kDisparityScale));
  }
  return image;
}

bool mentions(const io::SparseLidarCheck& check, const std::string& words) {
  for (const std::string& w : check.warnings) {
    if (w.find(words) != std::string::npos) return true;
  }
  return check.error.find(words) != std::string::npos;
}

TEST(SparseLidarCheck, DisparitiesGrowTowardTheGroundAndDepthsShrink) {
  EXPECT_GT(io::rowTrend(roadScan(false).view()), 2.5);
  EXPECT_LT(io::rowTrend(roadScan(true).view()), 0.4);
  EXPECT_EQ(io::rowTrend(Image<std::int16_t>(300, 100, kInvalidDisparity).view()), 0.0) << "no verdict";

  const io::SparseLidarCheck fine = io::checkSparseDisparity("/data/sparse.png", roadScan(false).view(), 300);
  EXPECT_TRUE(fine.error.empty()) << fine.error;
  EXPECT_TRUE(fine.warnings.empty()) << fine.warnings.front();
  const io::SparseLidarCheck depth = io::checkSparseDisparity("/data/sparse.png", roadScan(true).view(), 300);
  EXPECT_TRUE(depth.error.empty()) << depth.error;
  EXPECT_TRUE(mentions(depth, "shrink toward the bottom")) << "a depth map's values given as disparities";
  EXPECT_TRUE(mentions(depth, "-lidar_depth FILE -fb F"));
  // Converted from depths, a disparity map's values give the opposite trend.
  EXPECT_TRUE(io::checkSparseDepth("/data/sparse.png", roadScan(false).view()).warnings.empty());
  EXPECT_TRUE(mentions(io::checkSparseDepth("/data/d.png", roadScan(true).view()), "grow toward the bottom"));
}

TEST(SparseLidarCheck, ImpossibleDisparitiesAreAnErrorAndDepthNamesAWarning) {
  const io::SparseLidarCheck narrow = io::checkSparseDisparity("/data/sparse.png", roadScan(false).view(), 40);
  EXPECT_TRUE(mentions(narrow, "more than the image's width (40 px)")) << narrow.error;
  EXPECT_TRUE(mentions(io::checkSparseDisparity("/kitti/proj_depth/velodyne_raw/image_02/0000000005.png",
                                                roadScan(false).view(), 300),
                       "named like a depth map"));
  EXPECT_FALSE(mentions(io::checkSparseDisparity("/kitti/disp_depth_lidar.png", roadScan(false).view(), 300),
                        "named like"));
  EXPECT_TRUE(mentions(io::checkSparseDepth("/kitti/disp_occ_0/000000_10.png", roadScan(true).view()),
                       "named like a disparity map"));
}

TEST(SparseLidarCheck, KittiLidarDisparitiesPassAndTheSameScanAsDepthIsNamed) {
  const std::string dir = test::sharedDataRoot() + "/kitti_stereo_sparse_lidar_disparity_sample";
  if (!test::haveSharedData("kitti_stereo_sparse_lidar_disparity_sample")) GTEST_SKIP() << "no " << dir;
  const Image<std::int16_t> disparity = io::readKittiDisparity(dir + "/sparse_lidar_disparity.png");
  const io::SparseLidarCheck fine = io::checkSparseDisparity(dir + "/sparse_lidar_disparity.png", disparity.view(), 1242);
  EXPECT_TRUE(fine.error.empty() && fine.warnings.empty()) << fine.error << (fine.warnings.empty() ? "" : fine.warnings[0]);
  const double trend = io::rowTrend(disparity.view());
  EXPECT_GT(trend, 1.5);
  // The same points as depths (F = 721.5 px * 0.54 m), read as disparities.
  Image<std::int16_t> depth(disparity.width(), disparity.height(), kInvalidDisparity);
  for (int y = 0; y < disparity.height(); ++y) {
    for (int x = 0; x < disparity.width(); ++x) {
      const std::int16_t d = disparity(x, y);
      if (d != kInvalidDisparity && d > 0) {
        depth(x, y) = static_cast<std::int16_t>(std::lround(389.6 / (d / double(kDisparityScale)) * kDisparityScale));
      }
    }
  }
  const io::SparseLidarCheck named = io::checkSparseDisparity(dir + "/sparse_lidar_disparity.png", depth.view(), 1242);
  EXPECT_TRUE(mentions(named, "as depths do")) << "trend " << io::rowTrend(depth.view());
  std::printf("the KITTI sample's bottom/top median: %.2f as disparities, %.2f as depths\n", trend,
              io::rowTrend(depth.view()));
}

}  // namespace
}  // namespace lidar_sgm
