#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "common/synthetic_stereo.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "pcl/pcl_test_helpers.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

using lidar_sgm::MatchMode;
using lidar_sgm::SGMDensification;
using lidar_sgm::geometry::OutputFrame;
using lidar_sgm::geometry::StereoCalibration;
using lidar_sgm::test::lidarPointAt;

using lidar_sgm::test::cameraDepth;
using lidar_sgm::test::kWallDepth;
using lidar_sgm::test::pixelCodedImage;
using lidar_sgm::test::wallScan;

namespace {

StereoCalibration rig() { return lidar_sgm::test::pclRig(); }

pcl::PointCloud<pcl::RGB> toRgb(const lidar_sgm::Image<std::uint8_t>& gray) {
  pcl::PointCloud<pcl::RGB> image(static_cast<std::uint32_t>(gray.width()), static_cast<std::uint32_t>(gray.height()));
  for (int y = 0; y < gray.height(); ++y) {
    for (int x = 0; x < gray.width(); ++x) {
      image.at(x, y).r = image.at(x, y).g = image.at(x, y).b = gray(x, y);
    }
  }
  return image;
}

}  // namespace

TEST(SGMDensification, LidarOnlyGivesADenseCloudOnTheWallInTheInputFrame) {
  const StereoCalibration c = rig();
  auto scan = wallScan<pcl::PointXYZI>(c);
  SGMDensification<pcl::PointXYZI, pcl::PointXYZ> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  pcl::PointCloud<pcl::PointXYZ> dense;
  sgm.filter(dense);
  ASSERT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
  EXPECT_EQ(sgm.getLastMode(), MatchMode::LidarOnly);
  EXPECT_GE(dense.size(), 5 * scan->size());
  EXPECT_EQ(dense.height, 1u);
  EXPECT_EQ(dense.width, dense.size());
  EXPECT_TRUE(dense.is_dense);
  EXPECT_EQ(dense.header.frame_id, "velodyne");
  EXPECT_EQ(dense.header.stamp, 1234567u);
  int offWall = 0;
  for (const auto& p : dense) offWall += std::abs(cameraDepth(c, p.getVector3fMap()) - kWallDepth) > 0.02 ? 1 : 0;
  EXPECT_EQ(offWall, 0);
  // Timings and the projection's bookkeeping are reported.
  EXPECT_EQ(sgm.getProjectedLidar().stats.kept, scan->size());
  EXPECT_GT(sgm.getTimings().match, 0.0);
  EXPECT_EQ(sgm.getDisparityImage().width(), 160);
}

TEST(SGMDensification, OrganizedOutputKeepsEveryPixelWithNaNBeyondMaxDepth) {
  const StereoCalibration c = rig();
  auto scan = wallScan<pcl::PointXYZI>(c, /*farRight=*/true);
  SGMDensification<pcl::PointXYZI, pcl::PointXYZ> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setMaxDepth(20.0);  // the 50 m wall is cut
  sgm.setKeepOrganized(true);
  pcl::PointCloud<pcl::PointXYZ> organized;
  sgm.filter(organized);
  ASSERT_EQ(organized.width, 160u);
  ASSERT_EQ(organized.height, 96u);
  EXPECT_FALSE(organized.is_dense);
  EXPECT_TRUE(std::isnan(organized.at(150, 50).x));   // far wall: cut
  EXPECT_TRUE(std::isfinite(organized.at(40, 50).x));  // near wall
  EXPECT_NEAR(cameraDepth(c, organized.at(40, 50).getVector3fMap()), kWallDepth, 0.02);

  sgm.setKeepOrganized(false);
  pcl::PointCloud<pcl::PointXYZ> unorganized;
  sgm.filter(unorganized);
  std::size_t finite = 0;
  for (const auto& p : organized) finite += std::isfinite(p.x) ? 1 : 0;
  EXPECT_EQ(unorganized.size(), finite);
  EXPECT_TRUE(unorganized.is_dense);

  sgm.setStride(2);
  sgm.setKeepOrganized(true);
  sgm.filter(organized);
  EXPECT_EQ(organized.width, 80u);
  EXPECT_EQ(organized.height, 48u);
}

TEST(SGMDensification, CameraFrameIsTcamLidarTimesTheLidarFrame) {
  const StereoCalibration c = rig();
  auto scan = wallScan<pcl::PointXYZ>(c);
  SGMDensification<pcl::PointXYZ, pcl::PointXYZ> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  pcl::PointCloud<pcl::PointXYZ> inLidar;
  pcl::PointCloud<pcl::PointXYZ> inCamera;
  sgm.filter(inLidar);
  sgm.setOutputFrame(OutputFrame::Camera);
  sgm.setCameraFrameId("cam2");
  sgm.filter(inCamera);
  ASSERT_EQ(inLidar.size(), inCamera.size());
  ASSERT_FALSE(inLidar.empty());
  for (std::size_t i = 0; i < inLidar.size(); ++i) {
    const Eigen::Vector3d expected = c.T_cam_lidar * inLidar[i].getVector3fMap().cast<double>();
    ASSERT_LT((expected - inCamera[i].getVector3fMap().cast<double>()).norm(), 1e-4);
  }
  EXPECT_EQ(inCamera.header.frame_id, "cam2");
  EXPECT_EQ(inCamera.header.stamp, inLidar.header.stamp);
}

TEST(SGMDensification, HonoursIndices) {
  const StereoCalibration c = rig();
  auto scan = wallScan<pcl::PointXYZI>(c);
  std::vector<std::pair<int, int>> pixelOf;  // the pixel each input point was placed at
  for (int v = 2; v < c.height; v += 4) {
    for (int u = 0; u < c.width; u += 2) pixelOf.emplace_back(u, v);
  }
  ASSERT_EQ(pixelOf.size(), scan->size());
  // Interleave a decoy at 1.5 m in front of the wall after every wall point: only indices of
  // wall points are given, so positions in the index list and input indices differ.
  pcl::PointCloud<pcl::PointXYZI>::Ptr mixed(new pcl::PointCloud<pcl::PointXYZI>);
  mixed->header = scan->header;
  pcl::IndicesPtr wall(new pcl::Indices);
  for (std::size_t i = 0; i < scan->size(); ++i) {
    wall->push_back(static_cast<pcl::index_t>(mixed->size()));
    mixed->push_back((*scan)[i]);
    const Eigen::Vector3f p = lidarPointAt(c, pixelOf[i].first, pixelOf[i].second, 1.5);
    pcl::PointXYZI decoy;
    decoy.x = p.x();
    decoy.y = p.y();
    decoy.z = p.z();
    decoy.intensity = -1.0f;
    mixed->push_back(decoy);
  }
  std::reverse(wall->begin(), wall->end());  // and not in input order either
  SGMDensification<pcl::PointXYZI, pcl::PointXYZI> sgm;
  sgm.setInputCloud(mixed);
  sgm.setIndices(wall);
  sgm.setCalibration(c);
  sgm.setNumDisparities(128);  // 1.5 m is d = 66.7 px: searchable, so it would show
  sgm.setKeepOrganized(true);
  pcl::PointCloud<pcl::PointXYZI> dense;
  sgm.filter(dense);
  ASSERT_FALSE(dense.empty()) << sgm.getLastError();
  for (const auto& p : dense) {
    if (std::isfinite(p.x)) {
      ASSERT_NEAR(cameraDepth(c, p.getVector3fMap()), kWallDepth, 0.02);
    }
  }

  // sourceIndex names the input point, not its position in the index list: the input point
  // (even index i, wall point i / 2) was placed at the sample's pixel, and its intensity is
  // what the output carries there.
  const auto& projected = sgm.getProjectedLidar();
  EXPECT_EQ(projected.stats.input, wall->size());
  ASSERT_EQ(projected.sourceIndex.size(), projected.samples.size());
  ASSERT_EQ(projected.samples.size(), wall->size());
  for (std::size_t k = 0; k < projected.samples.size(); ++k) {
    const std::size_t source = projected.sourceIndex[k];
    ASSERT_LT(source, mixed->size());
    ASSERT_EQ(source % 2, 0u) << "a decoy: " << source;
    const auto& s = projected.samples[k];
    ASSERT_EQ(pixelOf[source / 2], std::make_pair(s.x, s.y)) << "sample " << k << " from input " << source;
    ASSERT_EQ(dense.at(s.x, s.y).intensity, (*mixed)[source].intensity);
  }

  sgm.setIndices(pcl::IndicesPtr(new pcl::Indices));
  sgm.filter(dense);
  EXPECT_TRUE(dense.empty());
  EXPECT_NE(sgm.getLastError().find("empty"), std::string::npos) << sgm.getLastError();
  EXPECT_TRUE(sgm.getProjectedLidar().samples.empty());
}

TEST(SGMDensification, ColorComesFromTheColorImageAtEachPointsPixel) {
  const StereoCalibration c = rig();
  SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
  sgm.setInputCloud(wallScan<pcl::PointXYZI>(c));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setColorImage(pixelCodedImage(c.width, c.height));
  sgm.setKeepOrganized(true);
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  ASSERT_EQ(dense.size(), 160u * 96u) << sgm.getLastError();
  int checked = 0;
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 160; ++x) {
      const auto& p = dense.at(x, y);
      if (!std::isfinite(p.x)) continue;
      ASSERT_EQ(p.r, x);
      ASSERT_EQ(p.g, y);
      ASSERT_EQ(p.b, 7);
      ++checked;
    }
  }
  EXPECT_GT(checked, 160 * 96 / 2);
}

TEST(SGMDensification, FusedWithAStereoPairAsPclImagesOrGrayViewsAgrees) {
  StereoCalibration c = rig();
  const auto stereo = lidar_sgm::test::makeStereo(c.width, c.height, [](double, double) { return 25.0; });
  auto scan = wallScan<pcl::PointXYZI>(c);
  SGMDensification<pcl::PointXYZI, pcl::PointXYZRGBA> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setStereoPair(toRgb(stereo.left), toRgb(stereo.right));
  pcl::PointCloud<pcl::PointXYZRGBA> fromPcl;
  sgm.filter(fromPcl);
  ASSERT_FALSE(fromPcl.empty()) << sgm.getLastError();
  EXPECT_EQ(sgm.getLastMode(), MatchMode::Fused);
  const lidar_sgm::Image<std::int16_t> disparityFromPcl = sgm.getDisparityImage();

  sgm.setStereoPair(stereo.left.view(), stereo.right.view());
  pcl::PointCloud<pcl::PointXYZRGBA> fromViews;
  sgm.filter(fromViews);
  ASSERT_EQ(fromViews.size(), fromPcl.size());
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) ASSERT_EQ(sgm.getDisparityImage()(x, y), disparityFromPcl(x, y));
  }
  // A 16-bit pair (8-bit * 257: the same order of intensities, so the same census) matches
  // identically, at full depth.
  lidar_sgm::Image<std::uint16_t> left16(c.width, c.height), right16(c.width, c.height);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      left16(x, y) = static_cast<std::uint16_t>(stereo.left(x, y) * 257);
      right16(x, y) = static_cast<std::uint16_t>(stereo.right(x, y) * 257);
    }
  }
  sgm.setStereoPair(left16.view(), right16.view());
  pcl::PointCloud<pcl::PointXYZRGBA> from16;
  sgm.filter(from16);
  ASSERT_EQ(from16.size(), fromPcl.size()) << sgm.getLastError();
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) ASSERT_EQ(sgm.getDisparityImage()(x, y), disparityFromPcl(x, y));
  }
  EXPECT_EQ(from16[from16.size() / 2].r, fromPcl[fromPcl.size() / 2].r);  // gray color from the high byte

  // The left image colors the points (gray here: r = g = b).
  const auto& p = fromPcl[fromPcl.size() / 2];
  EXPECT_EQ(p.r, p.g);
  EXPECT_EQ(p.g, p.b);
  int offWall = 0;
  for (const auto& q : fromPcl) offWall += std::abs(cameraDepth(c, q.getVector3fMap()) - kWallDepth) > 0.02 ? 1 : 0;
  EXPECT_EQ(offWall, 0);

  // A calibration without a size (KITTI object files) takes the pair's size.
  c.width = 0;
  c.height = 0;
  sgm.setCalibration(c);
  sgm.filter(fromViews);
  EXPECT_EQ(fromViews.size(), fromPcl.size()) << sgm.getLastError();
  sgm.clearStereoPair();
  sgm.filter(fromViews);
  EXPECT_TRUE(fromViews.empty());
  EXPECT_NE(sgm.getLastError().find("no image size"), std::string::npos) << sgm.getLastError();
}

TEST(SGMDensification, HalfScaleGivesAFullResolutionResult) {
  const StereoCalibration c = rig();
  const auto stereo = lidar_sgm::test::makeStereo(c.width, c.height, [](double, double) { return 25.0; });
  for (const bool fused : {false, true}) {
    SCOPED_TRACE(fused ? "fused" : "LiDAR-only");
    SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
    sgm.setInputCloud(wallScan<pcl::PointXYZI>(c));
    sgm.setCalibration(c);
    sgm.setNumDisparities(64);
    if (fused) sgm.setStereoPair(toRgb(stereo.left), toRgb(stereo.right));
    sgm.setKeepOrganized(true);
    sgm.setScale(0.5f);
    EXPECT_EQ(sgm.getScale(), 0.5f);
    EXPECT_EQ(sgm.getParameters().scale, 0.5f);
    pcl::PointCloud<pcl::PointXYZRGB> organized;
    sgm.filter(organized);
    ASSERT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
    EXPECT_EQ(organized.width, static_cast<std::uint32_t>(c.width));
    EXPECT_EQ(organized.height, static_cast<std::uint32_t>(c.height));
    EXPECT_EQ(sgm.getDisparityImage().width(), c.width);
    EXPECT_EQ(sgm.getDisparityImage().height(), c.height);
    // The wall is found, at the half-scale's precision (a full-resolution px of 25 is 0.16 m at 4 m).
    std::size_t valid = 0, onWall = 0;
    for (const auto& p : organized) {
      if (!std::isfinite(p.x)) continue;
      ++valid;
      onWall += std::abs(cameraDepth(c, p.getVector3fMap()) - kWallDepth) < 0.1 ? 1 : 0;
    }
    EXPECT_GT(valid, organized.size() / 2);
    EXPECT_GT(onWall, valid * 9 / 10);
  }
}

TEST(SGMDensification, ThreadCountNeverChangesTheResult) {
  const StereoCalibration c = rig();
  const auto stereo = lidar_sgm::test::makeStereo(c.width, c.height, [](double x, double) { return 20.0 + x / 16.0; });
  SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
  sgm.setInputCloud(wallScan<pcl::PointXYZI>(c, /*farRight=*/true));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setStereoPair(stereo.left.view(), stereo.right.view());
  for (const float scale : {1.0f, 0.5f}) {
    SCOPED_TRACE(scale);
    sgm.setScale(scale);
    sgm.setNumberOfThreads(1);
    EXPECT_EQ(sgm.getNumberOfThreads(), 1);
    pcl::PointCloud<pcl::PointXYZRGB> one;
    sgm.filter(one);
    ASSERT_FALSE(one.empty()) << sgm.getLastError();
    const lidar_sgm::Image<std::int16_t> disparityOne = sgm.getDisparityImage();
    for (const int threads : {2, 3, 0}) {
      SCOPED_TRACE(threads);
      sgm.setNumberOfThreads(threads);
      pcl::PointCloud<pcl::PointXYZRGB> many;
      sgm.filter(many);
      ASSERT_EQ(many.size(), one.size()) << sgm.getLastError();
      for (int y = 0; y < c.height; ++y) {
        for (int x = 0; x < c.width; ++x) ASSERT_EQ(sgm.getDisparityImage()(x, y), disparityOne(x, y)) << x << "," << y;
      }
      for (std::size_t i = 0; i < one.size(); ++i) {
        ASSERT_EQ(many[i].getVector3fMap(), one[i].getVector3fMap()) << i;
        ASSERT_EQ(many[i].rgba, one[i].rgba) << i;
      }
    }
  }
}

namespace {
/// Runs `breakIt` on a working setup and checks that filter() clears a filled output and
/// names `mention` in the error.
void expectFailure(const std::function<void(SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>&)>& breakIt,
                   const std::string& mention) {
  const StereoCalibration c = rig();
  SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
  sgm.setInputCloud(wallScan<pcl::PointXYZI>(c));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  breakIt(sgm);
  pcl::PointCloud<pcl::PointXYZRGB> out(3, 1);  // stale content must go
  sgm.filter(out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(out.width, 0u);
  EXPECT_NE(sgm.getLastError().find(mention), std::string::npos)
      << "expected '" << mention << "' in: " << sgm.getLastError();
}
}  // namespace

TEST(SGMDensification, BadPreconditionsGiveAnEmptyOutputAndANamedError) {
  using Sgm = SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>;
  expectFailure([](Sgm& s) { s.setInputCloud(pcl::PointCloud<pcl::PointXYZI>::Ptr(new pcl::PointCloud<pcl::PointXYZI>)); },
                "empty");
  expectFailure([](Sgm& s) {
    StereoCalibration bad = rig();
    bad.baseline = 0.0;
    s.setCalibration(bad);
  }, "baseline");
  expectFailure([](Sgm& s) { s.setAlpha(1.5f); }, "alpha");
  expectFailure([](Sgm& s) { s.setMaxDepth(-1.0); }, "maxDepth");
  expectFailure([](Sgm& s) {
    lidar_sgm::Parameters p;
    p.paths = 3;
    s.setParameters(p);
  }, "paths");
  expectFailure([](Sgm& s) { s.setScale(0.7f); }, "scale = 0.7");
  expectFailure([](Sgm& s) { s.setNumberOfThreads(-1); }, "threads = -1");
  expectFailure([](Sgm& s) {
    s.setScale(0.5f);
    s.setNumDisparities(48);
  }, "numDisparities = 48");
  expectFailure([](Sgm& s) {
    lidar_sgm::Image<std::uint8_t> left(160, 96), right(150, 96);
    s.setStereoPair(left.view(), right.view());
  }, "150x96");
  expectFailure([](Sgm& s) {
    lidar_sgm::Image<std::uint8_t> left(150, 96), right(150, 96);
    s.setStereoPair(left.view(), right.view());
  }, "calibration is for 160x96");
  expectFailure([](Sgm& s) { s.setColorImage(pcl::PointCloud<pcl::RGB>(160, 1)); }, "organized");
  expectFailure([](Sgm& s) {
    pcl::PointCloud<pcl::PointXYZI>::Ptr behind(new pcl::PointCloud<pcl::PointXYZI>);
    pcl::PointXYZI p;
    p.x = -5.0f;  // LiDAR x points forward: this is behind the camera
    behind->push_back(p);
    s.setInputCloud(behind);
  }, "1 behind the camera");
}

TEST(SGMDensification, NoInputCloudIsAnError) {
  SGMDensification<pcl::PointXYZ, pcl::PointXYZ> sgm;
  sgm.setCalibration(rig());
  pcl::PointCloud<pcl::PointXYZ> out(2, 1);
  sgm.filter(out);
  EXPECT_TRUE(out.empty());
  EXPECT_NE(sgm.getLastError().find("no input cloud"), std::string::npos) << sgm.getLastError();
}
