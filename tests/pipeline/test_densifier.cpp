// Densifier: the one pipeline behind every front end. Checks that it adds nothing to the
// matcher but the documented steps (projection, LiDAR-only crop, depth, reprojection), that its
// two inputs (a cloud, an already projected scan) are the same pipeline, and that bad input is
// named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <mutex>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"

namespace lidar_sgm {
namespace {

void expectError(const std::function<void()>& fn, const std::string& words);

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

  // The plane's LiDAR reaches 14.7 px: the range from the LiDAR is [0, 32), what the matcher got.
  EXPECT_TRUE(densifier.usedDisparityRange().fromLidar);
  EXPECT_EQ(densifier.usedParameters().numDisparities, 32);
  auto matcher = Matcher::create(Backend::CpuRef, densifier.usedParameters());
  const LidarPoints lidar = densifier.projected().lidarPoints();
  Image<std::int16_t> expected(kWidth, kHeight);
  matcher->compute(s.stereo.left.view(), s.stereo.right.view(), &lidar, expected.view());
  // Then the far scene's sub-pixel disparity anchored to the scan (the plane lies within 20 px).
  LidarAnchorBuffers buffers;
  const std::size_t anchored = anchorToLidar(expected.view(), densifier.projected().samples, LidarAnchorOptions{}, buffers);
  EXPECT_GT(anchored, 0u);
  EXPECT_EQ(densifier.filterStats().anchored, anchored);
  expectSameImage(densifier.disparity(), expected);
}

// The minimum confidence drops pixels from the disparity, the confidence, depth and cloud alike,
// and drops exactly those below the threshold.
TEST(Densifier, MinConfidenceDropsTheSamePixelsEverywhere) {
  const Scene s;
  Densifier all;
  all.setCalibration(s.calibration);
  all.setParameters(smallParameters());
  all.setBackend(Backend::CpuRef);
  all.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  all.setMinConfidence(0.0);
  all.run(s.scan);
  ASSERT_EQ(all.confidence().width(), kWidth);
  // A threshold between the lowest and highest confidence of the frame, so some pixels go.
  int lowest = 255, highest = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (all.disparity()(x, y) == kInvalidDisparity) {
        EXPECT_EQ(all.confidence()(x, y), 0);
        continue;
      }
      lowest = std::min<int>(lowest, all.confidence()(x, y));
      highest = std::max<int>(highest, all.confidence()(x, y));
    }
  }
  ASSERT_LT(lowest, highest);
  const int threshold = (lowest + highest + 1) / 2;
  Densifier some = std::move(all);
  some.setMinConfidence(threshold / 255.0);
  some.run(s.scan);
  Densifier reference;
  reference.setCalibration(s.calibration);
  reference.setParameters(smallParameters());
  reference.setBackend(Backend::CpuRef);
  reference.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  reference.setMinConfidence(0.0);
  reference.run(s.scan);
  long kept = 0, dropped = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int c = reference.confidence()(x, y);
      const bool keep = reference.disparity()(x, y) != kInvalidDisparity && c >= threshold;
      EXPECT_EQ(some.disparity()(x, y), keep ? reference.disparity()(x, y) : kInvalidDisparity) << x << "," << y;
      EXPECT_EQ(some.confidence()(x, y), keep ? c : 0);
      EXPECT_EQ(some.depth()(x, y) > 0.0f, keep && reference.depth()(x, y) > 0.0f);
      (keep ? kept : dropped) += 1;
    }
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(dropped, 0);
  EXPECT_EQ(static_cast<long>(some.cloud().size()), kept);

  EXPECT_THROW(some.setMinConfidence(1.5), std::invalid_argument);
  EXPECT_THROW(some.setMinConfidence(-0.1), std::invalid_argument);
  Parameters off = smallParameters();
  off.confidence = false;
  some.setParameters(off);
  expectError([&] { some.run(s.scan); }, "needs the confidence");
  some.setMinConfidence(0.0);
  some.run(s.scan);
  EXPECT_TRUE(some.confidence().empty());
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
  // Nothing to take a range from: the fixed one.
  EXPECT_FALSE(densifier.usedDisparityRange().fromLidar);
  EXPECT_EQ(densifier.usedParameters().numDisparities, smallParameters().numDisparities);
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

// ---- the disparity range from the LiDAR ------------------------------------------

constexpr int kNearWidth = 161;  // odd sizes on purpose
constexpr int kNearHeight = 45;

/// A street receding on the left (10 px) that comes near on the right: from x = 60 on the
/// disparity grows 0.6 px per column, to 70 px at the right border (far beyond a fixed 32).
double nearRightDisparity(double x, double /*y*/) { return 10.0 + 0.6 * std::max(0.0, x - 60.0); }

geometry::StereoCalibration nearRig() {
  geometry::StereoCalibration c = test::smallRig();
  c.width = kNearWidth;
  c.height = kNearHeight;
  c.K << 100, 0, 80, 0, 100, 22, 0, 0, 1;
  return c;
}

struct NearScene {
  geometry::StereoCalibration calibration = nearRig();
  test::SyntheticStereo stereo = test::makeStereo(kNearWidth, kNearHeight, nearRightDisparity);
  std::vector<Eigen::Vector3f> scan;
  NearScene() {
    for (int v = 4; v <= 40; v += 6) {
      for (int u = 1; u < kNearWidth; u += 3) {
        scan.push_back(test::lidarPointAt(calibration, u, v, calibration.focalBaseline() / nearRightDisparity(u, v)));
      }
    }
  }
};

Densifier nearDensifier(const NearScene& s, Backend backend) {
  Densifier densifier;
  densifier.setCalibration(s.calibration);
  densifier.setParameters(smallParameters());  // the fixed range: [0, 32)
  densifier.setBackend(backend);
  densifier.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  return densifier;
}

/// Pixels of column x (rows 2..kNearHeight-3) within 1 px of the GT.
int rightWithinOnePx(const Densifier& d, const NearScene& s, int x) {
  int n = 0;
  for (int y = 2; y < kNearHeight - 2; ++y) {
    const std::int16_t v = d.disparity()(x, y);
    n += v != kInvalidDisparity && std::abs(v / 16.0 - s.stereo.disparity(x, y)) < 1.0 ? 1 : 0;
  }
  return n;
}

TEST(Densifier, ANearObjectGetsARangeCoveringIt) {
  const NearScene s;
  Densifier densifier = nearDensifier(s, Backend::CpuRef);
  EXPECT_EQ(densifier.disparityRangeMode(), DisparityRangeMode::FromLidar);  // the default
  densifier.run(s.scan);
  const geometry::DisparityRange& range = densifier.usedDisparityRange();
  ASSERT_TRUE(range.fromLidar);
  EXPECT_GT(range.lidarMax, 65.0);  // the nearest points (up to 69.4 px) are no strays
  EXPECT_EQ(range.minDisparity, 0);
  EXPECT_EQ(range.numDisparities, 80);  // dMax + 8 px, rounded up to 16
  EXPECT_EQ(densifier.usedParameters().numDisparities, 80);
  EXPECT_EQ(densifier.parameters().numDisparities, 32);  // the fixed range is kept for later frames
  // The near columns (GT 61 and 64 px) are matched.
  EXPECT_GE(rightWithinOnePx(densifier, s, 145), kNearHeight - 8);
  EXPECT_GE(rightWithinOnePx(densifier, s, 150), kNearHeight - 8);

  Densifier fixed = nearDensifier(s, Backend::CpuRef);
  fixed.setDisparityRangeMode(DisparityRangeMode::Fixed);
  fixed.run(s.scan);
  EXPECT_FALSE(fixed.usedDisparityRange().fromLidar);
  EXPECT_EQ(fixed.usedParameters().numDisparities, 32);
  EXPECT_EQ(fixed.usedDisparityRange().describe(), "[0, 32) px (fixed)");
  EXPECT_EQ(rightWithinOnePx(fixed, s, 150), 0);  // beyond the fixed range
}

TEST(Densifier, TheRangeRuleIsTheDensifiers) {
  const NearScene s;
  Densifier densifier = nearDensifier(s, Backend::CpuRef);
  geometry::DisparityRangeRule rule;
  rule.maxNumDisparities = 48;
  densifier.setDisparityRangeRule(rule);
  densifier.run(s.scan);
  EXPECT_EQ(densifier.usedParameters().numDisparities, 48);
  EXPECT_TRUE(densifier.usedDisparityRange().capped);
  rule.maxNumDisparities = 40;  // not a multiple of 16: named
  densifier.setDisparityRangeRule(rule);
  expectError([&] { densifier.run(s.scan); }, "maxNumDisparities");
}

TEST(Densifier, TheRangeFromTheLidarIsTheSameOnEveryBackend) {
  const NearScene s;
  Densifier reference = nearDensifier(s, Backend::CpuRef);
  reference.run(s.scan);
  for (Backend backend : {Backend::Cpu, Backend::Auto}) {
    if (!isAvailable(backend)) continue;
    Densifier fast = nearDensifier(s, backend);
    fast.run(s.scan);
    EXPECT_EQ(fast.usedParameters().numDisparities, reference.usedParameters().numDisparities);
    expectSameImage(fast.disparity(), reference.disparity());
  }
  // At half scale the range is a multiple of 32 (96 here), and again the same everywhere.
  Parameters half = smallParameters();
  half.scale = 0.5f;
  Densifier halfReference = nearDensifier(s, Backend::CpuRef);
  halfReference.setParameters(half);
  halfReference.run(s.scan);
  EXPECT_EQ(halfReference.usedParameters().numDisparities, 96);
  Densifier halfFast = nearDensifier(s, Backend::Auto);
  halfFast.setParameters(half);
  halfFast.run(s.scan);
  expectSameImage(halfFast.disparity(), halfReference.disparity());
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
  filtered.setMinConfidence(0.0);  // the filters alone (the minimum confidence drops after them)
  const geometry::DenseCloud& cloud = filtered.run(s.scan);
  EXPECT_GT(filtered.filterStats().sky, 0u);

  Densifier unfiltered;
  unfiltered.setCalibration(s.calibration);
  unfiltered.setParameters(smallParameters());
  unfiltered.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  unfiltered.setMinConfidence(0.0);
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

// parallelFor tiles [0, count) with fixed ranges, each index in exactly one, at any thread
// count; counts beyond an int's range go in blocks (the ranges are recorded, not iterated).
TEST(DensifierParallelFor, TheRangesTileTheCountExactlyAtAnyThreadCount) {
  const std::size_t huge = (std::size_t{1} << 31) + 5;
  for (const int threads : {1, 2, 7}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{5}, std::size_t{433497}, huge}) {
      Densifier densifier;
      densifier.parameters().threads = threads;
      std::vector<std::pair<std::size_t, std::size_t>> ranges;
      std::mutex mutex;
      densifier.parallelFor(count, [&](std::size_t begin, std::size_t end) {
        const std::lock_guard<std::mutex> lock(mutex);
        ranges.emplace_back(begin, end);
      });
      std::sort(ranges.begin(), ranges.end());
      std::size_t next = 0;
      for (const auto& [begin, end] : ranges) {
        EXPECT_EQ(begin, next) << "threads " << threads << ", count " << count;
        EXPECT_LE(begin, end);
        next = end;
      }
      EXPECT_EQ(next, count) << "threads " << threads;
      EXPECT_LE(ranges.size(), static_cast<std::size_t>(threads) * (count / (std::size_t{1} << 31) + 1));
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
