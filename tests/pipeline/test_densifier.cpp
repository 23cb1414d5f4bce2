// Densifier: the one pipeline behind every front end. Checks that it adds nothing to the
// matcher but the documented steps (projection, LiDAR-only crop, depth, reprojection), that its
// two inputs (a cloud, an already projected scan) are the same pipeline, and that bad input is
// named.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 96;
constexpr int kHeight = 64;

/// fx = fy = 100, baseline 0.5 m: f*b = 50, so d = 10 px is z = 5 m. KITTI-like LiDAR mount.
geometry::StereoCalibration rig() {
  geometry::StereoCalibration c = test::smallRig();
  c.width = kWidth;
  c.height = kHeight;
  c.K << 100, 0, 48, 0, 100, 32, 0, 0, 1;
  return c;
}

/// A slanted plane: 10 px at the left border, 14.75 px at the right one.
double planeDisparity(double x, double /*y*/) { return 10.0 + 0.05 * x; }

Parameters smallParameters() {
  Parameters p;
  p.numDisparities = 32;
  return p;
}

/// LiDAR points on the plane: every 3rd column of rows 12, 18, ..., 48 (a scan with a top and
/// a bottom beam, so the LiDAR-only crop has something to cut).
std::vector<Eigen::Vector3f> planeScan(const geometry::StereoCalibration& c) {
  std::vector<Eigen::Vector3f> points;
  for (int v = 12; v <= 48; v += 6) {
    for (int u = 1; u < c.width; u += 3) {
      points.push_back(test::lidarPointAt(c, u, v, c.focalBaseline() / planeDisparity(u, v)));
    }
  }
  return points;
}

struct Scene {
  geometry::StereoCalibration calibration = rig();
  test::SyntheticStereo stereo = test::makeStereo(kWidth, kHeight, planeDisparity);
  std::vector<Eigen::Vector3f> scan = planeScan(calibration);
};

void expectSameImage(const Image<std::int16_t>& a, const Image<std::int16_t>& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  long differing = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) differing += a(x, y) != b(x, y) ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
}

long validCount(const Image<std::int16_t>& d) {
  long n = 0;
  for (int y = 0; y < d.height(); ++y) {
    for (int x = 0; x < d.width(); ++x) n += d(x, y) != kInvalidDisparity ? 1 : 0;
  }
  return n;
}

TEST(Densifier, FusedDisparityIsTheMatchersOnTheProjectedScan) {
  const Scene s;
  Densifier densifier;
  densifier.setCalibration(s.calibration);
  densifier.setParameters(smallParameters());
  densifier.setBackend(Backend::CpuRef);
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  densifier.run(s.scan);
  EXPECT_EQ(densifier.lastMode(), MatchMode::Fused);
  EXPECT_EQ(densifier.usedBackend(), Backend::CpuRef);
  EXPECT_EQ(densifier.projected().samples.size(), s.scan.size() - densifier.projected().stats.outsideImage -
                                                      densifier.projected().stats.occluded);

  auto matcher = Matcher::create(Backend::CpuRef, smallParameters());
  const LidarPoints lidar = densifier.projected().lidarPoints();
  Image<std::int16_t> expected(kWidth, kHeight);
  matcher->compute(s.stereo.left.view(), s.stereo.right.view(), &lidar, expected.view());
  expectSameImage(densifier.disparity(), expected);
}

TEST(Densifier, ACloudAndItsProjectionGiveTheSameFrame) {
  const Scene s;
  Densifier fromCloud;
  fromCloud.setCalibration(s.calibration);
  fromCloud.setParameters(smallParameters());
  fromCloud.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  fromCloud.run(s.scan);

  Densifier fromProjection;
  fromProjection.setCalibration(s.calibration);
  fromProjection.setParameters(smallParameters());
  fromProjection.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  const LidarPoints lidar = fromCloud.projected().lidarPoints();
  fromProjection.runProjected(&lidar);

  expectSameImage(fromProjection.disparity(), fromCloud.disparity());
  ASSERT_EQ(fromProjection.cloud().size(), fromCloud.cloud().size());
  for (std::size_t i = 0; i < fromCloud.cloud().size(); ++i) {
    EXPECT_EQ(fromProjection.cloud().points[i], fromCloud.cloud().points[i]) << i;
  }
  EXPECT_EQ(fromProjection.projected().samples.size(), lidar.size());
}

TEST(Densifier, StereoOnlyWithoutLidarIsTheMatchersStereoResult) {
  const Scene s;
  Densifier densifier;
  densifier.setParameters(smallParameters());
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  densifier.runProjected(nullptr);
  EXPECT_EQ(densifier.lastMode(), MatchMode::StereoOnly);
  // No calibration: the disparity only.
  EXPECT_TRUE(densifier.depth().empty());
  EXPECT_EQ(densifier.cloud().size(), 0u);

  auto matcher = Matcher::create(Backend::Auto, smallParameters());
  Image<std::int16_t> expected(kWidth, kHeight);
  matcher->compute(s.stereo.left.view(), s.stereo.right.view(), nullptr, expected.view());
  expectSameImage(densifier.disparity(), expected);
}

TEST(Densifier, DepthIsTheCloudsCameraZAndZeroWhereThereIsNone) {
  const Scene s;
  Densifier densifier;
  densifier.setCalibration(s.calibration);
  densifier.setParameters(smallParameters());
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  densifier.reprojectionOptions().frame = geometry::OutputFrame::Camera;
  densifier.reprojectionOptions().maxDepth = 4.8;  // cuts the plane's left part (z up to 5 m)
  const geometry::DenseCloud& cloud = densifier.run(s.scan);
  const Image<float>& depth = densifier.depth();
  ASSERT_EQ(depth.width(), kWidth);
  ASSERT_EQ(depth.height(), kHeight);
  long withDepth = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) withDepth += depth(x, y) > 0.0f ? 1 : 0;
  }
  ASSERT_EQ(static_cast<std::size_t>(withDepth), cloud.size());
  ASSERT_GT(cloud.size(), 0u);
  ASSERT_LT(static_cast<long>(cloud.size()), validCount(densifier.disparity()));  // the cut removed some
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geometry::PixelIndex p = cloud.pixels[i];
    EXPECT_EQ(depth(p.x, p.y), cloud.points[i].z()) << p.x << "," << p.y;
    EXPECT_LE(depth(p.x, p.y), 4.8f);
  }
  // Off, a run stops at the disparity.
  densifier.setComputeCloud(false);
  densifier.run(s.scan);
  EXPECT_TRUE(densifier.depth().empty());
  EXPECT_EQ(densifier.cloud().size(), 0u);
  EXPECT_GT(validCount(densifier.disparity()), 0);
}

TEST(Densifier, LidarOnlyIsCroppedToTheScanUnlessAskedNotTo) {
  const Scene s;
  Densifier densifier;
  densifier.setCalibration(s.calibration);
  Parameters params = smallParameters();
  densifier.setParameters(params);
  densifier.run(s.scan);
  EXPECT_EQ(densifier.lastMode(), MatchMode::LidarOnly);
  int top = kHeight;
  int bottom = -1;
  for (const LidarSample& p : densifier.projected().samples) {
    top = std::min(top, p.y);
    bottom = std::max(bottom, p.y);
  }
  const Image<std::int16_t> cropped = densifier.disparity();
  for (int y = 0; y < kHeight; ++y) {
    if (y >= top - params.lidarCoverageRows && y <= bottom + params.lidarCoverageRows) continue;
    for (int x = 0; x < kWidth; ++x) EXPECT_EQ(cropped(x, y), kInvalidDisparity) << x << "," << y;
  }
  densifier.setCropToScan(false);
  densifier.run(s.scan);
  EXPECT_GT(validCount(densifier.disparity()), validCount(cropped));
}

TEST(Densifier, AThirdCameraGivesTheMatchersTripleResult) {
  // The third camera sees the plane shifted vertically by the disparity times the ratio; a
  // plain copy is enough here: the test checks that the view reaches the matcher unchanged.
  const Scene s;
  Densifier densifier;
  densifier.setParameters(smallParameters());
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  densifier.setUpCamera(GrayImageView(s.stereo.left.view()), 1.0);
  densifier.runProjected(nullptr);

  auto matcher = Matcher::create(Backend::Auto, smallParameters());
  VerticalView up;
  up.up = s.stereo.left.view();
  up.baselineRatio = 1.0;
  Image<std::int16_t> expected(kWidth, kHeight);
  matcher->compute(s.stereo.left.view(), s.stereo.right.view(), up, nullptr, expected.view());
  EXPECT_TRUE(matcher->lastUsedUpCamera());
  expectSameImage(densifier.disparity(), expected);
}

void expectError(const std::function<void()>& fn, const std::string& words) {
  try {
    fn();
    FAIL() << "no error; expected one naming '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Densifier, BadInputIsNamed) {
  const Scene s;
  {
    Densifier d;
    d.setParameters(smallParameters());
    d.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
    expectError([&] { d.run(s.scan); }, "baseline must be positive");  // run(points) needs a calibration
  }
  {
    Densifier d;
    d.setCalibration(s.calibration);
    d.setParameters(smallParameters());
    expectError([&] { d.run({}); }, "empty");
    expectError([&] { d.runProjected(nullptr); }, "nothing to match");
  }
  {
    Densifier d;
    Image<std::uint8_t> small(kWidth - 1, kHeight);
    expectError([&] { d.setStereoPair(s.stereo.left.view(), small.view()); }, "right image is 95x64");
    expectError([&] { d.setUpCamera(GrayImageView(s.stereo.left.view()), 0.0); }, "baseline ratio");
    d.setUpCamera(GrayImageView(s.stereo.left.view()), 1.0);
    d.setParameters(smallParameters());
    const LidarPoints lidar(kWidth, kHeight, {{5, 5, 160}});
    expectError([&] { d.runProjected(&lidar); }, "needs the stereo pair");
  }
  {
    Densifier d;
    d.setCalibration(s.calibration);
    d.setParameters(smallParameters());
    Image<std::uint8_t> other(kWidth + 2, kHeight);
    d.setStereoPair(other.view(), other.view());
    expectError([&] { d.run(s.scan); }, "stereo pair is 98x64 but the calibration is for 96x64");
  }
  {
    Densifier d;
    d.setCalibration(s.calibration);
    Parameters bad = smallParameters();
    bad.alpha = 2.0f;
    d.setParameters(bad);
    expectError([&] { d.run(s.scan); }, "alpha");
  }
}

TEST(Densifier, KeepsWorkingAcrossFramesAndBackends) {
  const Scene s;
  Densifier densifier;
  densifier.setCalibration(s.calibration);
  densifier.setParameters(smallParameters());
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  densifier.setBackend(Backend::CpuRef);
  densifier.run(s.scan);
  const Image<std::int16_t> reference = densifier.disparity();
  densifier.setBackend(Backend::Auto);  // the fastest built backend: bit-identical by contract
  densifier.run(s.scan);
  expectSameImage(densifier.disparity(), reference);
  densifier.run(s.scan);
  expectSameImage(densifier.disparity(), reference);
}

}  // namespace
}  // namespace lidar_sgm

namespace lidar_sgm {
namespace {

// The output filters run between matching and reprojection: what they remove is missing from
// the disparity and the cloud alike, and they are the only difference to a run without them.
TEST(Densifier, OutputFiltersKeepDisparityAndCloudInAgreement) {
  Scene s;
  // A bright blank sky over rows 0..7 of both images (the scan's top beam is row 12).
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      s.stereo.left(x, y) = 230;
      s.stereo.right(x, y) = 230;
    }
  }
  Densifier filtered;
  filtered.setCalibration(s.calibration);
  filtered.setParameters(smallParameters());
  filtered.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  const geometry::DenseCloud& cloud = filtered.run(s.scan);
  EXPECT_GT(filtered.filterStats().sky, 0u);

  Densifier unfiltered;
  unfiltered.setCalibration(s.calibration);
  unfiltered.setParameters(smallParameters());
  unfiltered.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  unfiltered.outputFilters().sky.enabled = false;
  unfiltered.outputFilters().outliers.enabled = false;
  unfiltered.run(s.scan);
  EXPECT_EQ(unfiltered.filterStats().sky + unfiltered.filterStats().outliers, 0u);

  // Filtering only removes: every pixel either keeps the unfiltered disparity or lost it, and the
  // number lost is what the filters report.
  long lost = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::int16_t d = filtered.disparity()(x, y);
      if (d == kInvalidDisparity) {
        lost += unfiltered.disparity()(x, y) != kInvalidDisparity ? 1 : 0;
      } else {
        EXPECT_EQ(d, unfiltered.disparity()(x, y)) << x << "," << y;
      }
    }
  }
  EXPECT_EQ(static_cast<std::size_t>(lost), filtered.filterStats().sky + filtered.filterStats().outliers);
  // The cloud has one point per pixel with a depth, and those all have a remaining disparity
  // (a disparity <= 0 or beyond 80 m has no depth).
  long withDepth = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (filtered.depth()(x, y) <= 0.0f) continue;
      ++withDepth;
      EXPECT_NE(filtered.disparity()(x, y), kInvalidDisparity) << x << "," << y;
    }
  }
  ASSERT_EQ(static_cast<long>(cloud.size()), withDepth);
  EXPECT_GT(withDepth, validCount(filtered.disparity()) * 9 / 10);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geometry::PixelIndex p = cloud.pixels[i];
    EXPECT_NE(filtered.disparity()(p.x, p.y), kInvalidDisparity) << p.x << "," << p.y;
    EXPECT_GT(filtered.depth()(p.x, p.y), 0.0f);
  }
  for (int x = 0; x < kWidth; ++x) EXPECT_EQ(filtered.disparity()(x, 0), kInvalidDisparity) << x;  // the sky
}

}  // namespace
}  // namespace lidar_sgm
