// The LiDAR-anchored sub-pixel disparity (lidar_anchor.hpp): far pixels take the mean offset of
// the agreeing LiDAR points on their surface; near pixels, other surfaces, disagreeing points and
// invalid pixels are left alone; the result does not depend on the points' order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "lidar_sgm/pipeline/densifier_config.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 41;   // odd sizes on purpose
constexpr int kHeight = 23;

Image<std::int16_t> plane(int disparity16) {
  return Image<std::int16_t>(kWidth, kHeight, static_cast<std::int16_t>(disparity16));
}

/// LiDAR points on rows `y0`, `y0 + 5`, ... at every column, the matched disparity plus `offset16`.
std::vector<LidarSample> scanLines(const Image<std::int16_t>& matched, int offset16, int y0 = 2) {
  std::vector<LidarSample> samples;
  for (int y = y0; y < kHeight; y += 5) {
    for (int x = 0; x < kWidth; ++x) samples.push_back({x, y, matched(x, y) + offset16});
  }
  return samples;
}

TEST(LidarAnchor, AFarSurfaceTakesTheLidarsOffsetEverywhereBetweenTheLines) {
  Image<std::int16_t> d = plane(10 * 16);  // 10 px: far (the default anchors <= 20 px)
  LidarAnchorBuffers buffers;
  // The matcher 0.25 px short of the LiDAR everywhere (pixel locking): every pixel within reach of
  // a line moves by exactly those 4 x16 units, between the lines too.
  const std::size_t moved = anchorToLidar(d.view(), scanLines(d, 4), LidarAnchorOptions{}, buffers);
  EXPECT_EQ(moved, static_cast<std::size_t>(kWidth * kHeight));
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(d(x, y), 10 * 16 + 4) << x << "," << y;
  }
}

TEST(LidarAnchor, ASlantedSurfaceKeepsItsSlope) {
  // d = 8 px + x/8 px: the residual is what moves, not the LiDAR's own disparity, so the slope
  // between the points survives.
  Image<std::int16_t> d(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) d(x, y) = static_cast<std::int16_t>(8 * 16 + 2 * x);
  }
  const Image<std::int16_t> before = d;
  LidarAnchorBuffers buffers;
  anchorToLidar(d.view(), scanLines(before, -3), LidarAnchorOptions{}, buffers);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(d(x, y), before(x, y) - 3) << x << "," << y;
  }
}

TEST(LidarAnchor, NearPixelsDisagreeingPointsOtherSurfacesAndHolesAreLeftAlone) {
  Image<std::int16_t> d = plane(10 * 16);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 30; x < kWidth; ++x) d(x, y) = static_cast<std::int16_t>(40 * 16);  // near: 40 px
    d(15, y) = static_cast<std::int16_t>(11 * 16);  // another surface, 1 px nearer (gap 0.5 px)
  }
  d(5, 5) = kInvalidDisparity;
  const Image<std::int16_t> before = d;
  std::vector<LidarSample> samples = scanLines(before, 4);
  // A point 2 px off the matched surface (beyond the 1 px agreement) pulls nothing.
  samples.push_back({10, 10, 10 * 16 + 32});
  LidarAnchorBuffers buffers;
  anchorToLidar(d.view(), samples, LidarAnchorOptions{}, buffers);
  EXPECT_EQ(d(5, 5), kInvalidDisparity);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 30; x < kWidth; ++x) ASSERT_EQ(d(x, y), 40 * 16) << "near pixel " << x << "," << y;
    // The 1-px-nearer column takes only its own points' offset, never the plane's around it.
    ASSERT_EQ(d(15, y), 11 * 16 + 4) << y;
  }
  EXPECT_EQ(d(10, 10), 10 * 16 + 4);  // its own surface's points, not the disagreeing one
}

TEST(LidarAnchor, OffWhenDisabledOrWithoutPointsAndOrderFree) {
  const Image<std::int16_t> start = plane(12 * 16);
  std::vector<LidarSample> samples = scanLines(start, 5);
  std::mt19937 random(7);
  for (LidarSample& s : samples) s.disparity16 += static_cast<int>(random() % 11) - 5;  // noisy LiDAR
  LidarAnchorBuffers buffers;
  Image<std::int16_t> a = start;
  const std::size_t movedA = anchorToLidar(a.view(), samples, LidarAnchorOptions{}, buffers);
  std::shuffle(samples.begin(), samples.end(), random);
  Image<std::int16_t> b = start;
  const std::size_t movedB = anchorToLidar(b.view(), samples, LidarAnchorOptions{}, buffers);  // buffers reused
  EXPECT_GT(movedA, 0u);
  EXPECT_EQ(movedA, movedB);
  EXPECT_TRUE(std::equal(a.data(), a.data() + kWidth * kHeight, b.data()));

  LidarAnchorOptions off;
  off.enabled = false;
  Image<std::int16_t> c = start;
  EXPECT_EQ(anchorToLidar(c.view(), samples, off, buffers), 0u);
  EXPECT_EQ(anchorToLidar(c.view(), {}, LidarAnchorOptions{}, buffers), 0u);
  LidarAnchorOptions none;
  none.maxDisparity = 0;
  EXPECT_EQ(anchorToLidar(c.view(), samples, none, buffers), 0u);
  EXPECT_TRUE(std::equal(c.data(), c.data() + kWidth * kHeight, start.data()));
}

TEST(LidarAnchor, AMillionPointsInOnePixelAreStillAMean) {
  // 64-bit sums: no number of points sharing a window wraps them around.
  Image<std::int16_t> d = plane(10 * 16);
  const std::vector<LidarSample> samples(1000000, LidarSample{20, 11, 10 * 16 + 16});  // all 1 px nearer
  LidarAnchorBuffers buffers;
  anchorToLidar(d.view(), samples, LidarAnchorOptions{}, buffers);
  EXPECT_EQ(d(20, 11), 11 * 16);
  EXPECT_EQ(d(22, 13), 11 * 16);  // within reach of the Gaussian
  EXPECT_EQ(d(25, 11), 10 * 16);  // outside the window
}

TEST(LidarAnchor, ImpossibleOptionsAreRefusedByName) {
  const auto refused = [](void (*change)(LidarAnchorOptions&), const char* field) {
    LidarAnchorOptions o;
    change(o);
    try {
      validate(o);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
    DensifierConfig config;
    config.lidarAnchor = o;
    EXPECT_NE(validationError(config).find(field), std::string::npos);
  };
  refused([](LidarAnchorOptions& o) { o.maxDisparity = -1; }, "maxDisparity");
  refused([](LidarAnchorOptions& o) { o.halfWidth = 17; }, "halfWidth");
  refused([](LidarAnchorOptions& o) { o.halfHeight = -1; }, "halfHeight");
  refused([](LidarAnchorOptions& o) { o.sigma = 0; }, "sigma");
  refused([](LidarAnchorOptions& o) { o.agreement = 0; }, "agreement");
  refused([](LidarAnchorOptions& o) { o.surfaceGap = 9; }, "surfaceGap");
  EXPECT_NO_THROW(validate(LidarAnchorOptions{}));
}

}  // namespace
}  // namespace lidar_sgm
