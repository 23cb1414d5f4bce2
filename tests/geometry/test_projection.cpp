#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/geometry/projection.hpp"

using lidar_sgm::kInvalidDisparity;
using lidar_sgm::geometry::ProjectedLidar;
using lidar_sgm::geometry::ProjectionOptions;
using lidar_sgm::geometry::StereoCalibration;
using lidar_sgm::geometry::project;
using lidar_sgm::test::lidarPointAt;
using lidar_sgm::test::smallRig;

namespace {
ProjectionOptions withoutOcclusionFilter() {
  ProjectionOptions o;
  o.occlusion.enabled = false;
  return o;
}
}  // namespace

TEST(Projection, OnePointWorkedByHand) {
  StereoCalibration c = smallRig();
  Eigen::Matrix3d axes;  // the rig without its 2 degree yaw, so the numbers stay simple
  axes << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  c.T_cam_lidar.linear() = axes;
  // p_lidar = (9.8, 0.2, 0.4) -> p_cam = (-y, -z, x) + t = (-0.2, -0.5, 9.5)
  // u = 100 * -0.2 / 9.5 + 50 = 47.89 -> 48;  v = 100 * -0.5 / 9.5 + 30 = 24.74 -> 25
  // d = 50 / 9.5 = 5.263 px -> x16 = 84.2 -> 84
  const ProjectedLidar p = project({Eigen::Vector3f(9.8f, 0.2f, 0.4f)}, c, withoutOcclusionFilter());
  ASSERT_EQ(p.samples.size(), 1u);
  EXPECT_EQ(p.samples[0].x, 48);
  EXPECT_EQ(p.samples[0].y, 25);
  EXPECT_EQ(p.samples[0].disparity16, 84);
  EXPECT_EQ(p.sourceIndex[0], 0u);
  EXPECT_EQ(p.width, 101);
  EXPECT_EQ(p.height, 61);
}

TEST(Projection, EveryDroppedPointIsCountedOnceByReason) {
  const StereoCalibration c = smallRig();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  ProjectionOptions o = withoutOcclusionFilter();
  o.maxDepth = 60.0;
  const std::vector<Eigen::Vector3f> points = {
      lidarPointAt(c, 10, 10, 5.0),     // kept
      Eigen::Vector3f(nan, 0, 0),       // non-finite
      Eigen::Vector3f(1, inf, 0),       // non-finite
      Eigen::Vector3f(-10, 0, 0),       // behind the camera (LiDAR x backwards)
      lidarPointAt(c, 50, 30, 0.2),     // nearer than minDepth 0.5 m
      lidarPointAt(c, 50, 30, 70.0),    // beyond maxDepth 60 m
      lidarPointAt(c, 200, 30, 5.0),    // right of the image
      lidarPointAt(c, 50, -3, 5.0),     // above the image
      lidarPointAt(c, 100.4, 60.4, 5.0),  // rounds to the last pixel (100, 60): kept
      lidarPointAt(c, 100.6, 30, 5.0),  // rounds to column 101: outside
  };
  const ProjectedLidar p = project(points, c, o);
  EXPECT_EQ(p.stats.input, 10u);
  EXPECT_EQ(p.stats.nonFinite, 2u);
  EXPECT_EQ(p.stats.behindCamera, 1u);
  EXPECT_EQ(p.stats.outOfRange, 2u);
  EXPECT_EQ(p.stats.outsideImage, 3u);
  EXPECT_EQ(p.stats.occluded, 0u);
  EXPECT_EQ(p.stats.kept, 2u);
  ASSERT_EQ(p.samples.size(), 2u);
  EXPECT_EQ(p.sourceIndex[0], 0u);
  EXPECT_EQ(p.sourceIndex[1], 8u);
  EXPECT_EQ(p.samples[1].x, 100);
  EXPECT_EQ(p.samples[1].y, 60);
  EXPECT_NE(p.stats.describe().find("2 kept"), std::string::npos) << p.stats.describe();
}

TEST(Projection, KeepsEveryPointOfAPixelAndTheNearestWinsInTheSparseImage) {
  const StereoCalibration c = smallRig();
  // Three points on the ray through pixel (20, 15) at 5, 10 and 20 m: d = 10, 5, 2.5 px.
  const std::vector<Eigen::Vector3f> points = {lidarPointAt(c, 20, 15, 10.0), lidarPointAt(c, 20, 15, 5.0),
                                               lidarPointAt(c, 20, 15, 20.0)};
  const ProjectedLidar p = project(points, c, withoutOcclusionFilter());
  ASSERT_EQ(p.samples.size(), 3u);
  const lidar_sgm::LidarPoints lp = p.lidarPoints();
  ASSERT_EQ(lp.count(20, 15), 3);
  EXPECT_EQ(lp.begin(20, 15)[0], 80);  // 10 m: 5 px x16, in input order
  EXPECT_EQ(lp.begin(20, 15)[1], 160);
  EXPECT_EQ(lp.begin(20, 15)[2], 40);
  const auto sparse = p.sparseDisparity();
  EXPECT_EQ(sparse(20, 15), 160);
  EXPECT_EQ(sparse(21, 15), kInvalidDisparity);
}

TEST(Projection, OcclusionFilterDropsABackgroundPointInsideANearerSurface) {
  const StereoCalibration c = smallRig();
  // Foreground at 5 m (d = 10 px) on two beams, rows 20 and 28, column 40. Background at 20 m
  // (d = 2.5 px, 7.5 px farther):
  //   (41, 24): foreground above (rows 20..23) and below (25..28) within +-2 columns: dropped;
  //   (43, 24): 3 columns away, outside the window: kept;
  //   (40, 31): foreground above only (row 28): kept when enclosure is required, dropped when not.
  const std::vector<Eigen::Vector3f> points = {lidarPointAt(c, 40, 20, 5.0), lidarPointAt(c, 40, 28, 5.0),
                                               lidarPointAt(c, 41, 24, 20.0), lidarPointAt(c, 43, 24, 20.0),
                                               lidarPointAt(c, 40, 31, 20.0)};
  const ProjectedLidar enclosed = project(points, c);
  EXPECT_EQ(enclosed.stats.occluded, 1u);
  ASSERT_EQ(enclosed.samples.size(), 4u);
  EXPECT_EQ(enclosed.sourceIndex[2], 3u);
  EXPECT_EQ(enclosed.sourceIndex[3], 4u);

  ProjectionOptions anywhere;
  anywhere.occlusion.requireEnclosed = false;
  const ProjectedLidar p = project(points, c, anywhere);
  EXPECT_EQ(p.stats.occluded, 2u);
  ASSERT_EQ(p.samples.size(), 3u);
  EXPECT_EQ(p.sourceIndex[2], 3u);

  // Left and right enclosure counts too: foreground at columns 38 and 42 of row 24.
  const std::vector<Eigen::Vector3f> sideways = {lidarPointAt(c, 38, 24, 5.0), lidarPointAt(c, 42, 24, 5.0),
                                                 lidarPointAt(c, 40, 24, 20.0)};
  EXPECT_EQ(project(sideways, c).stats.occluded, 1u);
  // A nearer point in the very same pixel always hides a farther one.
  EXPECT_EQ(project({lidarPointAt(c, 40, 24, 5.0), lidarPointAt(c, 40, 24, 20.0)}, c).stats.occluded, 1u);
  EXPECT_EQ(project(points, c, withoutOcclusionFilter()).samples.size(), 5u);
}

TEST(Projection, OcclusionFilterKeepsASlantedSurface) {
  const StereoCalibration c = smallRig();
  // A ground-like surface: the disparity grows by 0.4 px per row (KITTI's road: ~0.33), from
  // 3 px at row 20 to 19 px at row 60, sampled every 2nd column and every 3rd row as a
  // LiDAR would. Within +-4 rows the nearest neighbour is at most 1.6 px nearer, under the
  // 2 px minimum gap, so nothing is dropped.
  std::vector<Eigen::Vector3f> points;
  for (int v = 20; v <= 60; v += 3) {
    const double d = 3.0 + 0.4 * (v - 20);
    for (int u = 0; u <= 100; u += 2) points.push_back(lidarPointAt(c, u, v, 50.0 / d));
  }
  const ProjectedLidar p = project(points, c);
  EXPECT_EQ(p.stats.occluded, 0u);
  EXPECT_EQ(p.samples.size(), points.size());
}

TEST(Projection, RelativeGapScalesWithDisparity) {
  const StereoCalibration c = smallRig();
  // Two points 4 rows apart at d = 40 and 44 px: the allowed gap for the farther one is
  // max(2, 10 % of 40) = 4 px and 44 - 40 is not above it: kept. At 40 and 45: 5 > 4: dropped.
  ProjectionOptions o;
  o.occlusion.requireEnclosed = false;
  const auto at = [&](double d, int v) { return lidarPointAt(c, 60, v, 50.0 / d); };
  EXPECT_EQ(project({at(40.0, 30), at(44.0, 34)}, c, o).stats.occluded, 0u);
  EXPECT_EQ(project({at(40.0, 30), at(45.0, 34)}, c, o).stats.occluded, 1u);
}

namespace {

// The occlusion filter's definition, pixel by pixel: whether a nearer point (x16 disparity above
// `limit16`) lies in the rectangle [x0, x1] x [y0, y1], clipped to the image.
bool nearerInByDefinition(const std::vector<std::vector<int>>& nearest, int x0, int x1, int y0, int y1, int limit16) {
  const int height = static_cast<int>(nearest.size());
  const int width = static_cast<int>(nearest[0].size());
  for (int y = std::max(y0, 0); y <= std::min(y1, height - 1); ++y) {
    for (int x = std::max(x0, 0); x <= std::min(x1, width - 1); ++x) {
      if (nearest[y][x] > limit16) return true;
    }
  }
  return false;
}

// The source indices project() should keep: each unfiltered sample tested against every pixel
// of its windows (OcclusionFilter's documentation).
std::vector<std::size_t> keptByDefinition(const ProjectedLidar& all, const lidar_sgm::geometry::OcclusionFilter& f) {
  std::vector<std::vector<int>> nearest(all.height, std::vector<int>(all.width, kInvalidDisparity));
  for (const auto& s : all.samples) nearest[s.y][s.x] = std::max(nearest[s.y][s.x], s.disparity16);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < all.samples.size(); ++i) {
    const auto& s = all.samples[i];
    const double gap = std::max(f.minGap, f.relativeGap * s.disparity16 / lidar_sgm::kDisparityScale);
    const int limit = s.disparity16 + static_cast<int>(std::floor(gap * lidar_sgm::kDisparityScale));
    const int x = s.x;
    const int y = s.y;
    const int hw = f.halfWidth;
    const int hh = f.halfHeight;
    bool occluded = nearest[y][x] > limit;
    if (!occluded && !f.requireEnclosed) occluded = nearerInByDefinition(nearest, x - hw, x + hw, y - hh, y + hh, limit);
    if (!occluded && f.requireEnclosed) {
      occluded = (nearerInByDefinition(nearest, x - hw, x + hw, y - hh, y - 1, limit) &&
                  nearerInByDefinition(nearest, x - hw, x + hw, y + 1, y + hh, limit)) ||
                 (nearerInByDefinition(nearest, x - hw, x - 1, y - hh, y + hh, limit) &&
                  nearerInByDefinition(nearest, x + 1, x + hw, y - hh, y + hh, limit));
    }
    if (!occluded) kept.push_back(all.sourceIndex[i]);
  }
  return kept;
}

}  // namespace

TEST(Projection, OcclusionFilterKeepsExactlyWhatItsWindowsDefine) {
  // Random scenes of near and far points on beam-like rows and scattered pixels, at the image's
  // edges too, through every window shape: project() must keep exactly the points the windows,
  // read pixel by pixel, leave visible.
  const StereoCalibration c = smallRig();
  std::mt19937 engine(7);
  for (int scene = 0; scene < 40; ++scene) {
    std::vector<Eigen::Vector3f> points;
    const int rowStep = 1 + scene % 5;
    for (int i = 0; i < 900; ++i) {
      const int u = static_cast<int>(engine() % 101u);
      const int v = scene % 2 == 0 ? static_cast<int>(engine() % 61u) : static_cast<int>(engine() % 61u) / rowStep * rowStep;
      const double z = engine() % 3u == 0 ? 2.0 + static_cast<int>(engine() % 100u) * 0.01 : 6.0 + static_cast<int>(engine() % 2000u) * 0.01;
      points.push_back(lidarPointAt(c, u, v, z));
    }
    const ProjectedLidar all = project(points, c, withoutOcclusionFilter());
    for (const int hw : {0, 1, 2, 7}) {
      for (const int hh : {0, 1, 4, 9}) {
        for (const bool enclosed : {true, false}) {
          ProjectionOptions o;
          o.occlusion.halfWidth = hw;
          o.occlusion.halfHeight = hh;
          o.occlusion.requireEnclosed = enclosed;
          const ProjectedLidar p = project(points, c, o);
          ASSERT_EQ(p.sourceIndex, keptByDefinition(all, o.occlusion))
              << "scene " << scene << ", window +-" << hw << " x +-" << hh << (enclosed ? ", enclosed" : "");
          EXPECT_EQ(p.stats.occluded + p.samples.size(), all.samples.size());
        }
      }
    }
  }
}

TEST(Projection, RejectsBadOptionsAndCalibration) {
  StereoCalibration c = smallRig();
  ProjectionOptions o;
  o.minDepth = 0.0;
  EXPECT_THROW(project({}, c, o), std::invalid_argument);
  o = ProjectionOptions();
  o.maxDepth = 0.4;
  EXPECT_THROW(project({}, c, o), std::invalid_argument);
  o = ProjectionOptions();
  o.occlusion.halfHeight = -1;
  EXPECT_THROW(project({}, c, o), std::invalid_argument);
  c.baseline = 0.0;
  EXPECT_THROW(project({}, c), std::invalid_argument);
}

TEST(Projection, EmptyCloudGivesNoSamples) {
  const ProjectedLidar p = project({}, smallRig());
  EXPECT_TRUE(p.samples.empty());
  EXPECT_EQ(p.stats.input, 0u);
  EXPECT_TRUE(p.lidarPoints().empty());
}
