// The fast passes around the matcher (src/pipeline/fast) against their specification, bit for
// bit: the scan's projection and the pair check at its points, the sky and outlier filters, the confidence of the valid pixels with its threshold, the
// depth image and the cloud; odd and tiny sizes, padded strides, 8- and 16-bit images, option
// values at the ends of their ranges, on 1, 2, 3 and 7 threads. Then the Densifier: the same
// frame on cpu_ref (the specification end to end) and on the fast backend gives the same bytes,
// and a second frame of the same size reuses the memory of the first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>
#include <random>
#include <string>
#include <vector>

#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"
#include "lidar_sgm/pipeline/min_confidence.hpp"
#include "lidar_sgm/pipeline/outlier_filter.hpp"
#include "lidar_sgm/pipeline/sky_mask.hpp"
#include "common/synthetic_stereo.hpp"
#include "geometry/geometry_test_helpers.hpp"
#include "pipeline/post_matcher_passes.hpp"
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
#include "pipeline/fast/fast_passes.hpp"
#endif

namespace lidar_sgm {
namespace {

struct Size {
  int width, height, stride;  ///< stride > width: a padded view
};
constexpr Size kSizes[] = {{1, 1, 1}, {2, 3, 5}, {5, 4, 5}, {17, 9, 24}, {64, 40, 64}, {131, 47, 140}, {631, 79, 640}};

/// An image in a buffer whose rows are `stride` elements apart; the padding holds garbage.
template <typename T>
struct Padded {
  std::vector<T> pixels;
  int width = 0, height = 0, stride = 0;
  Padded(Size s, T garbage) : pixels(static_cast<std::size_t>(s.stride) * s.height, garbage), width(s.width),
                              height(s.height), stride(s.stride) {}
  ImageView<T> view() { return ImageView<T>(pixels.data(), width, height, stride); }
  ImageView<const T> view() const { return ImageView<const T>(pixels.data(), width, height, stride); }
  T& operator()(int x, int y) { return pixels[static_cast<std::size_t>(y) * stride + x]; }
};

template <typename Expected, typename Actual>
::testing::AssertionResult samePixels(const Expected& expected, const Actual& actual) {
  if (expected.width != actual.width || expected.height != actual.height) {
    return ::testing::AssertionFailure() << "the sizes differ";
  }
  for (int y = 0; y < expected.height; ++y) {
    for (int x = 0; x < expected.width; ++x) {
      if (std::memcmp(&expected(x, y), &actual(x, y), sizeof(expected(x, y))) != 0) {
        return ::testing::AssertionFailure() << "first difference at (" << x << ", " << y << "): specification "
                                             << +expected(x, y) << ", fast " << +actual(x, y);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// Smooth patches (so that neighbours agree), noise, invalid pixels and the ends of int16.
Padded<std::int16_t> disparityOf(Size s, int invalidOneIn, std::mt19937& engine) {
  Padded<std::int16_t> d(s, 1234);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const auto pick = engine() % 40u;
      d(x, y) = engine() % static_cast<unsigned>(invalidOneIn) == 0 ? kInvalidDisparity
                : pick == 0                                          ? std::int16_t{32767}
                : pick == 1                                          ? std::int16_t{-32767}
                : pick < 6  ? static_cast<std::int16_t>(static_cast<int>(engine() % 4000u) - 200)
                            : static_cast<std::int16_t>(160 + 16 * ((x / 7 + y / 5) % 9) + static_cast<int>(engine() % 5u));
    }
  }
  return d;
}

/// A bright blank sky over the top rows (some of it over-exposed), a texture below; 16-bit
/// images carry the same levels in their high byte and noise in the low one.
template <typename T>
Padded<T> leftOf(Size s, int skyRows, std::mt19937& engine) {
  Padded<T> image(s, T{7});
  const int shift = sizeof(T) == 2 ? 8 : 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      int level = y < skyRows ? (x % 23 < 15 ? 255 : 200 + (x / 23) % 2) : static_cast<int>(30 + engine() % 200u);
      if (y < skyRows && engine() % 97u == 0) level = static_cast<int>(engine() % 256u);  // birds, wires
      image(x, y) = static_cast<T>((level << shift) | (shift != 0 ? static_cast<int>(engine() % 256u) : 0));
    }
  }
  return image;
}

/// A scan whose top beam wanders over the columns; some columns have no return at all.
std::vector<LidarSample> scanOf(Size s, std::mt19937& engine) {
  std::vector<LidarSample> samples;
  for (int x = 0; x < s.width; ++x) {
    if (engine() % 9u == 0) continue;
    const int top = s.height / 3 + static_cast<int>(engine() % 5u) - 2;
    for (int y = std::max(0, top); y < s.height; y += 3) {
      samples.push_back({x, y, static_cast<int>(150 + engine() % 300u)});
    }
  }
  return samples;
}

class FastPasses : public ::testing::TestWithParam<int> {
 protected:
  int threads() const { return GetParam(); }
};

#ifdef LIDAR_SGM_HAVE_FAST_PASSES

TEST_P(FastPasses, OutlierFilterIsTheSpecifications) {
  std::mt19937 engine(11);
  fast::FastPassBuffers buffers;  // one for every case: a buffer grown for one size serves the next
  for (const Size s : kSizes) {
    for (const int radius : {1, 2, 3, 8}) {
      // A few neighbours to all of them, no to the widest tolerance, few to most pixels invalid.
      for (int variant = 0; variant < 3; ++variant) {
        OutlierFilterOptions o;
        o.radius = radius;
        o.minNeighbours = variant == 0 ? 1 : variant == 1 ? 4 : 2 * radius * (radius + 1);
        o.relativeTolerance = variant == 0 ? 0.0 : variant == 1 ? 0.05 : 1.0;
        o.minTolerance = variant == 0 ? 0.0 : variant == 1 ? 0.5 : 64.0;
        const Padded<std::int16_t> input = disparityOf(s, variant == 0 ? 2 : variant == 1 ? 9 : 1000, engine);
        Padded<std::int16_t> expected = input;
        Padded<std::int16_t> actual = input;
        const std::size_t removed = removeOutliers(expected.view(), o);
        ASSERT_EQ(fast::removeOutliers(actual.view(), o, buffers, threads()), removed);
        ASSERT_TRUE(samePixels(expected.view(), std::as_const(actual).view()))
            << s.width << "x" << s.height << ", radius " << radius << ", variant " << variant;
        ASSERT_EQ(expected.pixels, actual.pixels) << "the padding must stay as it was";
      }
    }
  }
  OutlierFilterOptions bad;
  bad.radius = 9;
  Padded<std::int16_t> d = disparityOf({5, 4, 5}, 3, engine);
  EXPECT_THROW(fast::removeOutliers(d.view(), bad, buffers, threads()), std::invalid_argument);
  OutlierFilterOptions off;
  off.enabled = false;
  EXPECT_EQ(fast::removeOutliers(d.view(), off, buffers, threads()), 0u);
}

template <typename T>
void expectSameSky(Size s, int threads, std::mt19937& engine, fast::FastPassBuffers& buffers) {
  SkyFilterOptions o;
  const std::vector<LidarSample> samples = scanOf(s, engine);
  const Padded<T> left = leftOf<T>(s, s.height / 3, engine);
  for (int variant = 0; variant < 8; ++variant) {
    o.farTest = variant % 2 == 1;
    o.textureRadius = variant < 2 ? 3 : variant < 4 ? 1 : variant < 6 ? 32 : 2;
    o.brightLevel = variant == 6 ? 256 : variant == 7 ? 0 : 160;
    o.textureThreshold = variant == 7 ? 510.0 : variant == 4 ? 0.0 : 1.0;
    o.marginRows = variant == 5 ? 0 : 2;
    o.columnRadius = variant == 3 ? 0 : variant == 5 ? 256 : 8;
    o.farSlack = variant == 3 ? 64.0 : 1.0;
    for (const bool withImage : {true, false}) {
      const GrayImageView image = withImage ? GrayImageView(left.view()) : GrayImageView();
      const Padded<std::int16_t> input = disparityOf(s, 7, engine);
      Padded<std::int16_t> expected = input;
      Padded<std::int16_t> actual = input;
      const std::size_t removed = removeSky(expected.view(), samples, image, o);
      ASSERT_EQ(fast::removeSky(actual.view(), samples, image, o, buffers, threads), removed)
          << s.width << "x" << s.height << ", variant " << variant << (withImage ? "" : ", no image");
      ASSERT_TRUE(samePixels(expected.view(), std::as_const(actual).view())) << "variant " << variant;
      ASSERT_EQ(expected.pixels, actual.pixels) << "the padding must stay as it was";
    }
  }
}

TEST_P(FastPasses, SkyFilterIsTheSpecifications) {
  std::mt19937 engine(12);
  fast::FastPassBuffers buffers;
  for (const Size s : kSizes) {
    expectSameSky<std::uint8_t>(s, threads(), engine, buffers);
    expectSameSky<std::uint16_t>(s, threads(), engine, buffers);
  }
}

TEST_P(FastPasses, SkyFilterEdgeCases) {
  fast::FastPassBuffers buffers;
  const Size s{17, 9, 20};
  std::mt19937 engine(13);
  Padded<std::int16_t> d = disparityOf(s, 5, engine);
  // No samples, or the filter off: nothing; a sample outside the image: the specification's error.
  EXPECT_EQ(fast::removeSky(d.view(), {}, GrayImageView(), SkyFilterOptions{}, buffers, threads()), 0u);
  SkyFilterOptions off;
  off.enabled = false;
  EXPECT_EQ(fast::removeSky(d.view(), scanOf(s, engine), GrayImageView(), off, buffers, threads()), 0u);
  EXPECT_THROW(fast::removeSky(d.view(), {{17, 0, 16}}, GrayImageView(), {}, buffers, threads()), std::invalid_argument);
  SkyFilterOptions bad;
  bad.textureRadius = 0;
  EXPECT_THROW(fast::removeSky(d.view(), scanOf(s, engine), GrayImageView(), bad, buffers, threads()),
               std::invalid_argument);
  const Padded<std::uint8_t> small({16, 9, 16}, 0);
  EXPECT_THROW(fast::removeSky(d.view(), scanOf(s, engine), small.view(), {}, buffers, threads()), std::invalid_argument);
  // The scan reaches the top row everywhere: no candidate row.
  std::vector<LidarSample> top;
  for (int x = 0; x < s.width; ++x) top.push_back({x, 0, 100});
  const Padded<std::int16_t> before = d;
  EXPECT_EQ(fast::removeSky(d.view(), top, GrayImageView(), {}, buffers, threads()), 0u);
  EXPECT_EQ(d.pixels, before.pixels);
}

TEST_P(FastPasses, ConfidenceOfValidPixelsIsTheSpecifications) {
  std::mt19937 engine(14);
  for (const Size s : kSizes) {
    for (const double minConfidence : {0.0, 1e-12, 0.5, 1.0}) {
      const Padded<std::int16_t> input = disparityOf(s, 4, engine);
      Padded<std::uint8_t> matched(s, 99);
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) matched(x, y) = static_cast<std::uint8_t>(engine() % 256u);
      }
      // The specification: the Densifier's copy, then applyMinConfidence.
      Padded<std::int16_t> expected = input;
      Padded<std::uint8_t> expectedConfidence(s, 55);
      for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
          expectedConfidence(x, y) = expected(x, y) == kInvalidDisparity ? 0 : matched(x, y);
        }
      }
      if (minConfidence > 0.0) applyMinConfidence(expected.view(), expectedConfidence.view(), minConfidence);
      Padded<std::int16_t> actual = input;
      Padded<std::uint8_t> confidence(s, 55);
      fast::confidenceOfValidPixels(actual.view(), std::as_const(matched).view(), confidence.view(), minConfidence,
                                    threads());
      ASSERT_EQ(expected.pixels, actual.pixels) << s.width << "x" << s.height << ", min " << minConfidence;
      ASSERT_EQ(expectedConfidence.pixels, confidence.pixels) << s.width << "x" << s.height << ", min " << minConfidence;
    }
  }
  Padded<std::int16_t> d({5, 4, 5}, 0);
  Padded<std::uint8_t> c({5, 4, 5}, 0);
  const Padded<std::uint8_t> wrong({4, 4, 4}, 0);
  EXPECT_THROW(fast::confidenceOfValidPixels(d.view(), wrong.view(), c.view(), 0.5, threads()), std::invalid_argument);
  EXPECT_THROW(fast::confidenceOfValidPixels(d.view(), c.view(), c.view(), 1.5, threads()), std::invalid_argument);
}

geometry::StereoCalibration calibrationOf(Size s) {
  geometry::StereoCalibration c = test::smallRig();
  c.width = s.width;
  c.height = s.height;
  c.K << 721.5, 0, 0.37 * s.width, 0, 721.5, 0.46 * s.height, 0, 0, 1;
  return c;
}

::testing::AssertionResult sameCloud(const geometry::DenseCloud& a, const geometry::DenseCloud& b) {
  if (a.width != b.width || a.height != b.height || a.isDense != b.isDense || a.size() != b.size() ||
      a.pixels.size() != b.pixels.size()) {
    return ::testing::AssertionFailure() << "the clouds' shapes differ: " << a.width << "x" << a.height << " vs "
                                         << b.width << "x" << b.height;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(a.points[i].data(), b.points[i].data(), 3 * sizeof(float)) != 0 ||
        a.pixels[i].x != b.pixels[i].x || a.pixels[i].y != b.pixels[i].y) {
      return ::testing::AssertionFailure() << "point " << i << " differs";
    }
  }
  return ::testing::AssertionSuccess();
}

TEST_P(FastPasses, LidarAnchorIsTheSpecifications) {
  std::mt19937 engine(23);
  LidarAnchorBuffers specBuffers;
  LidarAnchorBuffers fastBuffers;  // one for every case: kept between calls as the Densifier keeps it
  fast::FastPassBuffers passBuffers;
  for (const Size s : kSizes) {
    const Padded<std::int16_t> matched = disparityOf(s, 7, engine);
    // Points near the matched disparity (most agree, some do not), some off the image.
    std::vector<LidarSample> samples;
    for (int y = 0; y < s.height; y += 2) {
      for (int x = -1; x <= s.width; ++x) {
        const bool inside = x >= 0 && x < s.width;
        const int base = inside && matched.view()(x, y) > 0 ? matched.view()(x, y) : 200;
        samples.push_back({x, y, std::max(1, base + static_cast<int>(engine() % 41u) - 20)});
      }
    }
    LidarAnchorOptions wide;
    wide.maxDisparity = 300.0;  // every valid pixel of disparityOf's patches is far
    LidarAnchorOptions flat = wide;
    flat.halfHeight = 0;
    flat.surfaceGap = 8.0;
    for (const LidarAnchorOptions& o : {LidarAnchorOptions{}, wide, flat}) {
      Padded<std::int16_t> expected = matched;
      Padded<std::int16_t> actual = matched;
      const std::size_t expectedMoved = anchorToLidar(expected.view(), samples, o, specBuffers);
      const std::size_t actualMoved = fast::anchorToLidar(actual.view(), samples, o, fastBuffers, passBuffers, threads());
      ASSERT_TRUE(samePixels(expected.view(), std::as_const(actual).view())) << s.width << "x" << s.height;
      EXPECT_EQ(actualMoved, expectedMoved);
    }
  }
}

TEST_P(FastPasses, DepthAndCloudAreTheSpecifications) {
  std::mt19937 engine(15);
  fast::FastPassBuffers buffers;
  geometry::DenseCloud cloud;  // one for every case: its vectors keep their memory
  Image<float> depth;
  for (const Size s : kSizes) {
    const geometry::StereoCalibration c = calibrationOf(s);
    const Padded<std::int16_t> d = disparityOf(s, 5, engine);
    // The depth of d16 = 300 exactly, and the double below it: the last point kept, then dropped.
    const double atBoundary = c.focalBaseline() * kDisparityScale / 300;
    for (const double maxDepth : {80.0, 3.0, std::numeric_limits<double>::infinity(), atBoundary,
                                  std::nextafter(atBoundary, 0.0)}) {
      Image<float> expectedDepth;
      geometry::depthImage(d.view(), c.focalBaseline(), maxDepth, expectedDepth);
      fast::depthImage(d.view(), c.focalBaseline(), maxDepth, depth, buffers, threads());
      ASSERT_TRUE(samePixels(expectedDepth.view(), std::as_const(depth).view())) << s.width << "x" << s.height;
      for (const int stride : {1, 2, 3}) {
        for (const bool organized : {false, true}) {
          for (const auto frame : {geometry::OutputFrame::Lidar, geometry::OutputFrame::Camera}) {
            geometry::ReprojectionOptions o;
            o.maxDepth = maxDepth;
            o.stride = stride;
            o.keepOrganized = organized;
            o.frame = frame;
            fast::reproject(d.view(), c, o, cloud, buffers, threads());
            ASSERT_TRUE(sameCloud(geometry::reproject(d.view(), c, o), cloud))
                << s.width << "x" << s.height << ", stride " << stride << (organized ? ", organized" : "");
          }
        }
      }
    }
  }
  const Padded<std::int16_t> d = disparityOf({5, 4, 5}, 5, engine);
  geometry::ReprojectionOptions bad;
  bad.stride = 0;
  EXPECT_THROW(fast::reproject(d.view(), calibrationOf({5, 4, 5}), bad, cloud, buffers, threads()), std::invalid_argument);
  EXPECT_THROW(fast::reproject(d.view(), calibrationOf({6, 4, 6}), {}, cloud, buffers, threads()), std::invalid_argument);
  EXPECT_THROW(fast::depthImage(d.view(), 0.0, 80.0, depth, buffers, threads()), std::invalid_argument);
}

::testing::AssertionResult sameProjection(const geometry::ProjectedLidar& a, const geometry::ProjectedLidar& b) {
  if (a.width != b.width || a.height != b.height || a.samples.size() != b.samples.size() ||
      a.sourceIndex.size() != b.sourceIndex.size()) {
    return ::testing::AssertionFailure() << "the projections' shapes differ: " << a.samples.size() << " vs "
                                         << b.samples.size() << " samples";
  }
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    const LidarSample& p = a.samples[i];
    const LidarSample& q = b.samples[i];
    if (p.x != q.x || p.y != q.y || p.disparity16 != q.disparity16 || a.sourceIndex[i] != b.sourceIndex[i]) {
      return ::testing::AssertionFailure() << "sample " << i << " differs";
    }
  }
  const geometry::ProjectionStats& s = a.stats;
  const geometry::ProjectionStats& t = b.stats;
  if (s.input != t.input || s.nonFinite != t.nonFinite || s.behindCamera != t.behindCamera ||
      s.outOfRange != t.outOfRange || s.outsideImage != t.outsideImage || s.occluded != t.occluded ||
      s.kept != t.kept) {
    return ::testing::AssertionFailure() << "the counts differ: " << s.describe() << " vs " << t.describe();
  }
  return ::testing::AssertionSuccess();
}

TEST_P(FastPasses, ProjectionIsTheSpecifications) {
  std::mt19937 engine(31);
  fast::FastPassBuffers buffers;
  geometry::ProjectedLidar actual;  // one for every case: its vectors keep their memory
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const Size s : kSizes) {
    const geometry::StereoCalibration c = calibrationOf(s);
    // A far wall, a near box over part of it (background points inside its silhouette), a few
    // points per pixel, and points each check drops: NaN, behind the camera, too near, outside.
    std::vector<Eigen::Vector3f> points;
    for (int k = 0; k < std::min(2 * s.width * s.height, 20000) + 40; ++k) {
      const double u = -2.0 + (s.width + 3.0) * static_cast<double>(engine() % 10000u) / 10000.0;
      const double v = -2.0 + (s.height + 3.0) * static_cast<double>(engine() % 10000u) / 10000.0;
      const bool box = u > 0.3 * s.width && u < 0.6 * s.width && v > 0.2 * s.height && v < 0.7 * s.height;
      double z = box && engine() % 3u != 0 ? 5.0 + static_cast<double>(engine() % 100u) / 100.0
                                           : 20.0 + static_cast<double>(engine() % 500u) / 100.0;
      const auto pick = engine() % 50u;
      if (pick == 0) z = -z;    // behind the camera
      if (pick == 1) z = 0.2;   // nearer than minDepth
      points.push_back(test::lidarPointAt(c, u, v, z));
      if (pick == 2) points.back().x() = nan;
      if (pick == 3) points.back().z() = std::numeric_limits<float>::infinity();
    }
    geometry::ProjectionOptions open;
    open.occlusion.requireEnclosed = false;
    geometry::ProjectionOptions off;
    off.occlusion.enabled = false;
    geometry::ProjectionOptions wide;
    wide.occlusion.halfWidth = 5;
    wide.occlusion.halfHeight = 0;
    wide.maxDepth = 23.0;
    for (const geometry::ProjectionOptions& o : {geometry::ProjectionOptions{}, open, off, wide}) {
      const geometry::ProjectedLidar expected = geometry::project(points, c, o);
      fast::project(points, c, o, actual, buffers, threads());
      ASSERT_TRUE(sameProjection(expected, actual)) << s.width << "x" << s.height;
    }
    // The first half of the cloud: fewer points than the buffers hold from the last call.
    points.resize(points.size() / 2);
    fast::project(points, c, {}, actual, buffers, threads());
    ASSERT_TRUE(sameProjection(geometry::project(points, c, {}), actual)) << s.width << "x" << s.height;
  }
  geometry::ProjectionOptions bad;
  bad.minDepth = 0.0;
  EXPECT_THROW(fast::project({}, calibrationOf({5, 4, 5}), bad, actual, buffers, threads()), std::invalid_argument);
  fast::project({}, calibrationOf({5, 4, 5}), {}, actual, buffers, threads());
  EXPECT_TRUE(actual.samples.empty());
  EXPECT_EQ(actual.stats.input, 0u);
}

TEST_P(FastPasses, PairOrientationFromLidarIsTheSpecifications) {
  const test::SyntheticStereo stereo =
      test::makeStereo(301, 83, [](double x, double y) { return 6.0 + 0.03 * x + 0.05 * y; });
  std::mt19937 engine(37);
  fast::FastPassBuffers buffers;
  // Fewer samples than tests allowed, then more (every step-th sample is tested), some far off.
  for (const int count : {0, 1, 2, 700, 9001}) {
    std::vector<LidarSample> samples;
    for (int k = 0; k < count; ++k) {
      const int x = static_cast<int>(engine() % 301u);
      const int y = static_cast<int>(engine() % 83u);
      const int d16 = engine() % 4u == 0 ? static_cast<int>(engine() % 600u)
                                         : static_cast<int>(16.0 * stereo.disparity(x, y) + 0.5f);
      samples.push_back({x, y, d16});
    }
    for (const bool swapped : {false, true}) {
      const GrayImageView left(swapped ? stereo.right.view() : stereo.left.view());
      const GrayImageView right(swapped ? stereo.left.view() : stereo.right.view());
      const PairOrientation expected = pairOrientationFromLidar(left, right, samples);
      const PairOrientation actual = fast::pairOrientationFromLidar(left, right, samples, buffers, threads());
      EXPECT_TRUE(actual.fromLidar);
      EXPECT_EQ(actual.tested, expected.tested) << count << " samples";
      EXPECT_EQ(actual.givenWins, expected.givenWins) << count << " samples";
      EXPECT_EQ(actual.swappedWins, expected.swappedWins) << count << " samples";
      if (count == 9001) {
        EXPECT_EQ(actual.looksSwapped(), swapped) << "the scene must decide both ways";
      }
    }
  }
}

TEST_P(FastPasses, PairOrientationFromStereoIsTheSpecifications) {
  fast::FastPassBuffers buffers;
  // Tiny images (no grid row fits), odd sizes, a textured pair both ways and a flat one; ranges
  // that leave no disparity inside the image and ranges from below zero.
  for (const Size s : {Size{5, 4, 5}, Size{64, 40, 64}, Size{301, 83, 301}}) {
    const test::SyntheticStereo stereo =
        test::makeStereo(s.width, s.height, [](double x, double) { return 5.0 + 0.02 * x; });
    const Image<std::uint8_t> flat(s.width, s.height, 90);
    for (const int minDisparity : {-3, 2}) {
      for (const int numDisparities : {16, 48}) {
        for (const bool swapped : {false, true}) {
          for (const bool textured : {true, false}) {
            if (!textured && swapped) continue;  // a flat image votes nowhere, either way
            const GrayImageView left(textured ? (swapped ? stereo.right.view() : stereo.left.view()) : flat.view());
            const GrayImageView right(swapped ? stereo.left.view() : stereo.right.view());
            const PairOrientation expected = pairOrientationFromStereo(left, right, minDisparity, numDisparities);
            const PairOrientation actual =
                fast::pairOrientationFromStereo(left, right, minDisparity, numDisparities, buffers, threads());
            EXPECT_FALSE(actual.fromLidar);
            EXPECT_EQ(actual.tested, expected.tested) << s.width << "x" << s.height;
            EXPECT_EQ(actual.givenWins, expected.givenWins) << s.width << "x" << s.height;
            EXPECT_EQ(actual.swappedWins, expected.swappedWins) << s.width << "x" << s.height;
            if (s.width == 301 && textured && minDisparity == 2 && numDisparities == 16) {
              EXPECT_EQ(actual.looksSwapped(), swapped) << "the scene must decide both ways";
            }
          }
        }
      }
    }
  }
}

#endif  // LIDAR_SGM_HAVE_FAST_PASSES

// ---- the Densifier: cpu_ref runs the specification, the fast backend the fast passes -----------

/// A slanted plane under a bright blank sky, a scan of it with a top beam: every pass has work.
struct DensifierScene {
  static constexpr int kWidth = 131;  // odd sizes on purpose
  static constexpr int kHeight = 61;
  geometry::StereoCalibration calibration;
  test::SyntheticStereo stereo = test::makeStereo(kWidth, kHeight, [](double x, double) { return 9.0 + 0.04 * x; });
  std::vector<Eigen::Vector3f> scan;
  DensifierScene() {
    calibration = test::smallRig();
    calibration.width = kWidth;
    calibration.height = kHeight;
    calibration.K << 100, 0, 65, 0, 100, 30, 0, 0, 1;
    for (int y = 0; y < 14; ++y) {
      for (int x = 0; x < kWidth; ++x) stereo.left(x, y) = stereo.right(x, y) = 250;
    }
    for (int v = 20; v < kHeight; v += 4) {
      for (int u = 1; u < kWidth; u += 2) {
        scan.push_back(test::lidarPointAt(calibration, u, v, calibration.focalBaseline() / (9.0 + 0.04 * u)));
      }
    }
  }
};

Densifier densifierFor(const DensifierScene& s, Backend backend, int threads, bool organized) {
  Densifier d;
  d.setCalibration(s.calibration);
  d.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  d.parameters().numDisparities = 32;
  d.parameters().threads = threads;
  d.reprojectionOptions().keepOrganized = organized;
  d.setBackend(backend);
  return d;
}

TEST_P(FastPasses, TheDensifiersOutputsAreTheSameOnCpuRefAndTheFastBackend) {
  const DensifierScene s;
  for (const bool organized : {false, true}) {
    Densifier reference = densifierFor(s, Backend::CpuRef, 1, organized);
    Densifier fastest = densifierFor(s, Backend::Auto, threads(), organized);
    reference.run(s.scan);
    fastest.run(s.scan);
    ASSERT_GT(reference.filterStats().sky, 0u) << "the scene must give the sky filter work";
    EXPECT_EQ(fastest.filterStats().sky, reference.filterStats().sky);
    EXPECT_EQ(fastest.filterStats().outliers, reference.filterStats().outliers);
    EXPECT_TRUE(samePixels(reference.disparity().view(), fastest.disparity().view()));
    EXPECT_TRUE(samePixels(reference.confidence().view(), fastest.confidence().view()));
    EXPECT_TRUE(samePixels(reference.depth().view(), fastest.depth().view()));
    EXPECT_TRUE(sameCloud(reference.cloud(), fastest.cloud()));
  }
}

TEST_P(FastPasses, ASecondFrameOfTheSameSizeReusesTheFirstOnesMemory) {
  if (!PostMatcherPasses::fastBuilt()) GTEST_SKIP() << "the fast passes are not built";
  const DensifierScene s;
  Densifier d = densifierFor(s, Backend::Auto, threads(), false);
  d.run(s.scan);
  const void* disparity = d.disparity().data();
  const void* confidence = d.confidence().data();
  const void* depth = d.depth().data();
  const void* points = d.cloud().points.data();
  const void* pixels = d.cloud().pixels.data();
  d.run(s.scan);
  EXPECT_EQ(d.disparity().data(), disparity);
  EXPECT_EQ(d.confidence().data(), confidence);
  EXPECT_EQ(d.depth().data(), depth);
  EXPECT_EQ(d.cloud().points.data(), points);
  EXPECT_EQ(d.cloud().pixels.data(), pixels);
}

INSTANTIATE_TEST_SUITE_P(Threads, FastPasses, ::testing::Values(1, 2, 3, 7),
                         [](const ::testing::TestParamInfo<int>& p) { return std::to_string(p.param); });

}  // namespace
}  // namespace lidar_sgm
