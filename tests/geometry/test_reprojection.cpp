#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/geometry/scan_extent.hpp"

using lidar_sgm::Image;
using lidar_sgm::kInvalidDisparity;
using lidar_sgm::geometry::DenseCloud;
using lidar_sgm::geometry::OutputFrame;
using lidar_sgm::geometry::ProjectionOptions;
using lidar_sgm::geometry::ReprojectionOptions;
using lidar_sgm::geometry::StereoCalibration;
using lidar_sgm::test::lidarPointAt;
using lidar_sgm::test::smallRig;

namespace {

/// Depth of a plane/box scene at each pixel: a wall at 10 m, and a box face at 6 m covering
/// columns 30..60, rows 10..40.
double sceneDepth(int u, int v) { return (u >= 30 && u <= 60 && v >= 10 && v <= 40) ? 6.0 : 10.0; }

}  // namespace

TEST(Reprojection, RoundTripThroughTheSparseDisparityReturnsTheLidarPoints) {
  const StereoCalibration c = smallRig();
  // One LiDAR point per pixel centre of the scene, so projection needs no pixel rounding and
  // the only loss is the x16 disparity: at most 1/32 px, i.e. 10 m * (1/32) / 5 px = 6 cm at
  // this rig's f*b = 50; KITTI's f*b = 387 makes it 8 mm at 10 m. So: rebuild the same scene
  // with KITTI's focal length and baseline and require < 1 cm.
  StereoCalibration kitti = c;
  kitti.width = 1242;
  kitti.height = 375;
  kitti.K << 721.5377, 0, 609.5593, 0, 721.5377, 172.854, 0, 0, 1;
  kitti.baseline = 0.537;
  std::vector<Eigen::Vector3f> scene;
  for (int v = 0; v < kitti.height; v += 3) {
    for (int u = 0; u < kitti.width; u += 2) {
      const double z = (u >= 400 && u <= 800 && v >= 100 && v <= 300) ? 6.0 : 10.0;
      scene.push_back(lidarPointAt(kitti, u, v, z));
    }
  }
  ProjectionOptions p;
  p.occlusion.enabled = false;
  const auto projected = lidar_sgm::geometry::project(scene, kitti, p);
  ASSERT_EQ(projected.samples.size(), scene.size());
  const Image<std::int16_t> sparse = projected.sparseDisparity();
  const DenseCloud cloud = lidar_sgm::geometry::reproject(sparse.view(), kitti);
  ASSERT_EQ(cloud.size(), scene.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    // Unorganized output is in row-major pixel order, as was the scene.
    worst = std::max(worst, static_cast<double>((cloud.points[i] - scene[i]).norm()));
  }
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(worst, 0.0);  // the x16 quantisation is real; an exact match would mean no round trip
}

TEST(Reprojection, CameraFrameDiffersExactlyByTcamLidar) {
  const StereoCalibration c = smallRig();
  Image<std::int16_t> disparity(c.width, c.height);
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) disparity(u, v) = static_cast<std::int16_t>(std::lround(16 * 50.0 / sceneDepth(u, v)));
  }
  ReprojectionOptions lidarFrame;
  ReprojectionOptions cameraFrame;
  cameraFrame.frame = OutputFrame::Camera;
  const DenseCloud inLidar = lidar_sgm::geometry::reproject(disparity.view(), c, lidarFrame);
  const DenseCloud inCamera = lidar_sgm::geometry::reproject(disparity.view(), c, cameraFrame);
  ASSERT_EQ(inLidar.size(), inCamera.size());
  ASSERT_EQ(inLidar.size(), static_cast<std::size_t>(c.width * c.height));
  for (std::size_t i = 0; i < inLidar.size(); ++i) {
    const Eigen::Vector3d expected = c.T_cam_lidar * inLidar.points[i].cast<double>();
    ASSERT_LT((expected - inCamera.points[i].cast<double>()).norm(), 1e-5) << "point " << i;
  }
  // Camera frame by hand at pixel (50, 30) = the principal point: (0, 0, z) with z = 50/d.
  const std::size_t centre = 30 * static_cast<std::size_t>(c.width) + 50;
  EXPECT_EQ(inCamera.pixels[centre].x, 50);
  EXPECT_EQ(inCamera.pixels[centre].y, 30);
  EXPECT_NEAR(inCamera.points[centre].x(), 0.0f, 1e-6);
  EXPECT_NEAR(inCamera.points[centre].y(), 0.0f, 1e-6);
  EXPECT_NEAR(inCamera.points[centre].z(), 50.0 / (disparity(50, 30) / 16.0), 1e-5);
}

TEST(Reprojection, OrganizedKeepsEveryPixelWithNaNAndStrideSamples) {
  StereoCalibration c = smallRig();
  Image<std::int16_t> disparity(c.width, c.height, kInvalidDisparity);
  disparity(0, 0) = 80;    // 5 px -> 10 m
  disparity(2, 0) = 0;     // zero disparity: infinitely far, no point
  disparity(4, 2) = -16;   // negative: no point
  disparity(100, 60) = 160;
  ReprojectionOptions o;
  o.keepOrganized = true;
  o.stride = 2;
  const DenseCloud cloud = lidar_sgm::geometry::reproject(disparity.view(), c, o);
  // 101 columns, stride 2 -> 0, 2, ..., 100 = 51; 61 rows -> 31.
  EXPECT_EQ(cloud.width, 51);
  EXPECT_EQ(cloud.height, 31);
  ASSERT_EQ(cloud.size(), 51u * 31u);
  EXPECT_FALSE(cloud.isDense);
  int valid = 0;
  for (const auto& p : cloud.points) valid += p.allFinite() ? 1 : 0;
  EXPECT_EQ(valid, 2);
  EXPECT_TRUE(cloud.points[0].allFinite());
  EXPECT_TRUE(std::isnan(cloud.points[1].x()));  // pixel (2, 0), zero disparity
  EXPECT_TRUE(cloud.points.back().allFinite());  // pixel (100, 60)
  EXPECT_EQ(cloud.pixels.back().x, 100);
  EXPECT_EQ(cloud.pixels.back().y, 60);
  EXPECT_EQ(cloud.pixels[51].y, 2);  // second organized row is image row 2

  o.keepOrganized = false;
  const DenseCloud unorganized = lidar_sgm::geometry::reproject(disparity.view(), c, o);
  EXPECT_EQ(unorganized.size(), 2u);
  EXPECT_EQ(unorganized.width, 2);
  EXPECT_EQ(unorganized.height, 1);
  EXPECT_TRUE(unorganized.isDense);
}

TEST(Reprojection, MaxDepthCutsFarPixels) {
  const StereoCalibration c = smallRig();
  Image<std::int16_t> disparity(c.width, c.height, kInvalidDisparity);
  disparity(10, 10) = 16;   // 1 px -> 50 m
  disparity(11, 10) = 8;    // 0.5 px -> 100 m: beyond the default 80 m
  disparity(12, 10) = 800;  // 50 px -> 1 m
  EXPECT_EQ(lidar_sgm::geometry::reproject(disparity.view(), c).size(), 2u);
  ReprojectionOptions o;
  o.maxDepth = 40.0;
  EXPECT_EQ(lidar_sgm::geometry::reproject(disparity.view(), c, o).size(), 1u);
  o.maxDepth = std::numeric_limits<double>::infinity();
  EXPECT_EQ(lidar_sgm::geometry::reproject(disparity.view(), c, o).size(), 3u);
}

// A ground truth read from KITTI's 1/256 px files goes in as float, unrounded: where its
// disparity is a multiple of 1/16 px, exactly the points of the x16 image; <= 0 and NaN give none.
TEST(Reprojection, FloatDisparityGivesTheSamePointsAsItsX16Image) {
  const StereoCalibration c = smallRig();
  Image<std::int16_t> disparity16(c.width, c.height, kInvalidDisparity);
  Image<float> disparity(c.width, c.height, 0.0f);
  for (int y = 0; y < c.height; y += 3) {
    for (int x = 0; x < c.width; x += 2) {
      disparity16(x, y) = static_cast<std::int16_t>(16 + (x * 7 + y * 13) % 300);
      disparity(x, y) = disparity16(x, y) / 16.0f;
    }
  }
  disparity(1, 1) = std::numeric_limits<float>::quiet_NaN();
  disparity(3, 1) = -2.0f;
  for (OutputFrame frame : {OutputFrame::Lidar, OutputFrame::Camera}) {
    ReprojectionOptions o;
    o.frame = frame;
    const DenseCloud expected = lidar_sgm::geometry::reproject(disparity16.view(), c, o);
    const DenseCloud cloud = lidar_sgm::geometry::reproject(disparity.view(), c, o);
    ASSERT_EQ(cloud.size(), expected.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_EQ(cloud.points[i], expected.points[i]) << i;
      EXPECT_EQ(cloud.pixels[i].x, expected.pixels[i].x);
      EXPECT_EQ(cloud.pixels[i].y, expected.pixels[i].y);
    }
  }
  // A sub-x16 disparity is kept as it is: 12.3 px -> z = 50 / 12.3 m at the principal point.
  disparity(50, 30) = 12.3f;
  ReprojectionOptions camera;
  camera.frame = OutputFrame::Camera;
  const DenseCloud cloud = lidar_sgm::geometry::reproject(disparity.view(), c, camera);
  bool found = false;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.pixels[i].x != 50 || cloud.pixels[i].y != 30) continue;
    found = true;
    EXPECT_FLOAT_EQ(cloud.points[i].z(), static_cast<float>(50.0 / static_cast<double>(12.3f)));
  }
  EXPECT_TRUE(found);
  Image<float> wrong(c.width, c.height + 1, 1.0f);
  EXPECT_THROW(lidar_sgm::geometry::reproject(wrong.view(), c), std::invalid_argument);
}

TEST(Reprojection, RejectsMismatchedSizesAndBadOptions) {
  const StereoCalibration c = smallRig();
  Image<std::int16_t> wrong(c.width + 1, c.height, 16);
  try {
    lidar_sgm::geometry::reproject(wrong.view(), c);
    ADD_FAILURE() << "accepted a 102x61 disparity for a 101x61 calibration";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("102x61"), std::string::npos) << e.what();
  }
  Image<std::int16_t> right(c.width, c.height, 16);
  ReprojectionOptions o;
  o.stride = 0;
  EXPECT_THROW(lidar_sgm::geometry::reproject(right.view(), c, o), std::invalid_argument);
  o = ReprojectionOptions();
  o.maxDepth = 0.0;
  EXPECT_THROW(lidar_sgm::geometry::reproject(right.view(), c, o), std::invalid_argument);
}

TEST(ScanExtent, ClearsAboveTheTopAndBelowTheBottomSampleOfEachColumn) {
  // 10x20 image, all valid. Samples: column 2 at rows 8 and 12; column 7 at row 5.
  Image<std::int16_t> disparity(10, 20, 160);
  const std::vector<lidar_sgm::LidarSample> samples = {{2, 8, 160}, {2, 12, 160}, {7, 5, 160}};
  // margin 2 rows, 1 column: columns 1..3 keep rows 6..14; columns 6..8 keep rows 3..7;
  // columns 0, 4, 5, 9 have no sample within 1 column: cleared.
  const std::size_t cleared = lidar_sgm::geometry::cropToScanRows(disparity.view(), samples, 2, 1);
  EXPECT_EQ(cleared, 200u - 3 * 9 - 3 * 5);
  EXPECT_EQ(disparity(2, 5), kInvalidDisparity);
  EXPECT_EQ(disparity(2, 6), 160);
  EXPECT_EQ(disparity(3, 14), 160);
  EXPECT_EQ(disparity(3, 15), kInvalidDisparity);
  EXPECT_EQ(disparity(8, 3), 160);
  EXPECT_EQ(disparity(8, 8), kInvalidDisparity);
  EXPECT_EQ(disparity(0, 10), kInvalidDisparity);
  EXPECT_EQ(disparity(5, 5), kInvalidDisparity);
  EXPECT_THROW(lidar_sgm::geometry::cropToScanRows(disparity.view(), {{10, 0, 16}}, 2, 1), std::invalid_argument);
  EXPECT_THROW(lidar_sgm::geometry::cropToScanRows(disparity.view(), samples, -1, 1), std::invalid_argument);
}
