// The output filters on small hand-made images: the sky above a scan goes, a wall above it with
// the left image's texture (or darker than the sky) stays; an isolated point goes, thin poles
// stay; bad options are named.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/pipeline/outlier_filter.hpp"
#include "lidar_sgm/pipeline/sky_mask.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 33;   // odd sizes: no filter may assume even ones
constexpr int kHeight = 27;
constexpr int kTopBeamRow = 12;

Image<std::int16_t> constantDisparity(int width, int height, double d) {
  return Image<std::int16_t>(width, height, static_cast<std::int16_t>(d * kDisparityScale));
}

/// A scan whose top beam is row kTopBeamRow, every other column, beams every 3 rows below it.
std::vector<LidarSample> scan(double d) {
  std::vector<LidarSample> samples;
  for (int y = kTopBeamRow; y < kHeight; y += 3) {
    for (int x = 0; x < kWidth; x += 2) samples.push_back({x, y, static_cast<int>(d * kDisparityScale)});
  }
  return samples;
}

/// Rows [0, skyRows) at `skyLevel` (blank), the rest a texture (a pseudo-random pattern).
Image<std::uint8_t> leftImage(int skyRows, std::uint8_t skyLevel, bool texturedTop = false) {
  Image<std::uint8_t> image(kWidth, kHeight);
  unsigned state = 12345;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      state = state * 1103515245u + 12345u;
      const auto noise = static_cast<std::uint8_t>(40 + (state >> 16) % 120);
      image(x, y) = (y < skyRows && !texturedTop) ? skyLevel : noise;
    }
  }
  return image;
}

int invalidInRows(const Image<std::int16_t>& d, int firstRow, int endRow) {
  int n = 0;
  for (int y = firstRow; y < endRow; ++y) {
    for (int x = 0; x < d.width(); ++x) n += d(x, y) == kInvalidDisparity ? 1 : 0;
  }
  return n;
}

TEST(SkyFilter, RemovesABrightBlankSkyAboveTheScan) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  const Image<std::uint8_t> left = leftImage(10, 230);
  const std::size_t removed = removeSky(disparity.view(), scan(10.0), left.view(), SkyFilterOptions{});
  // Rows whose texture window (radius 3) holds no gradient: 0..5 (row 6's window reaches row 9,
  // whose vertical gradient crosses into the texture).
  EXPECT_EQ(invalidInRows(disparity, 0, 6), 6 * kWidth);
  // The textured rows and everything the scan covers stay.
  EXPECT_EQ(invalidInRows(disparity, 10, kHeight), 0);
  EXPECT_EQ(removed, static_cast<std::size_t>(invalidInRows(disparity, 0, kHeight)));
}

TEST(SkyFilter, KeepsATexturedWallAboveTheScan) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  const Image<std::uint8_t> left = leftImage(10, 230, true);
  EXPECT_EQ(removeSky(disparity.view(), scan(10.0), left.view(), SkyFilterOptions{}), 0u);
  EXPECT_EQ(invalidInRows(disparity, 0, kHeight), 0);
}

TEST(SkyFilter, KeepsABlankWallDarkerThanTheSky) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  const Image<std::uint8_t> left = leftImage(10, 90);  // a plain facade in the shade
  EXPECT_EQ(removeSky(disparity.view(), scan(10.0), left.view(), SkyFilterOptions{}), 0u);
}

TEST(SkyFilter, StopsAtTheFirstStructureFromTheTop) {
  // A textured wall on rows 0..4, then a bright blank band, then the scan: the band is below
  // structure (a bright wall under a cornice), not sky, and stays.
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  Image<std::uint8_t> left = leftImage(kHeight, 230, true);
  for (int y = 5; y < 11; ++y) {
    for (int x = 0; x < kWidth; ++x) left(x, y) = 230;
  }
  EXPECT_EQ(removeSky(disparity.view(), scan(10.0), left.view(), SkyFilterOptions{}), 0u);
}

TEST(SkyFilter, FarTestRemovesWhatLiesBeyondTheScanWhenOn) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < kWidth; ++x) disparity(x, y) = 3 * kDisparityScale;  // beyond the LiDAR's 10 px
  }
  const Image<std::uint8_t> left = leftImage(0, 0, true);  // textured everywhere: only "far" can act
  SkyFilterOptions options;
  Image<std::int16_t> kept = disparity;
  EXPECT_EQ(removeSky(kept.view(), scan(10.0), left.view(), options), 0u);  // off by default
  options.farTest = true;
  EXPECT_EQ(removeSky(disparity.view(), scan(10.0), left.view(), options), static_cast<std::size_t>(5 * kWidth));
  EXPECT_EQ(invalidInRows(disparity, 5, kHeight), 0);
}

TEST(SkyFilter, NothingWithoutAScanOrWhenOff) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  const Image<std::uint8_t> left = leftImage(10, 230);
  EXPECT_EQ(removeSky(disparity.view(), {}, left.view(), SkyFilterOptions{}), 0u);
  SkyFilterOptions off;
  off.enabled = false;
  EXPECT_EQ(removeSky(disparity.view(), scan(10.0), left.view(), off), 0u);
}

TEST(SkyFilter, SixteenBitImagesAreReadByTheirHighByte) {
  Image<std::int16_t> d8 = constantDisparity(kWidth, kHeight, 10.0);
  Image<std::int16_t> d16 = d8;
  const Image<std::uint8_t> left = leftImage(10, 230);
  Image<std::uint16_t> left16(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) left16(x, y) = static_cast<std::uint16_t>(left(x, y) << 8 | 0x5a);
  }
  EXPECT_EQ(removeSky(d8.view(), scan(10.0), left.view(), {}), removeSky(d16.view(), scan(10.0), left16.view(), {}));
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(d8(x, y), d16(x, y));
  }
}

TEST(SkyFilter, BadInputIsNamed) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  SkyFilterOptions o;
  o.textureRadius = 0;
  try {
    removeSky(disparity.view(), scan(10.0), GrayImageView(), o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("textureRadius"), std::string::npos) << e.what();
  }
  const Image<std::uint8_t> small(5, 5, 0);
  EXPECT_THROW(removeSky(disparity.view(), scan(10.0), small.view(), {}), std::invalid_argument);
  EXPECT_THROW(removeSky(disparity.view(), {{kWidth, 0, 16}}, GrayImageView(), {}), std::invalid_argument);
}

TEST(OutlierFilter, RemovesAnIsolatedPointAndKeepsTheSurface) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  disparity(16, 13) = 30 * kDisparityScale;  // a lone wrong match, 3x nearer
  EXPECT_EQ(removeOutliers(disparity.view(), OutlierFilterOptions{}), 1u);
  EXPECT_EQ(disparity(16, 13), kInvalidDisparity);
  EXPECT_EQ(invalidInRows(disparity, 0, kHeight), 1);
}

TEST(OutlierFilter, RemovesAFlyingPointBetweenTwoSurfaces) {
  // Foreground (20 px) left of column 16, background (5 px) right of it, and on the edge one
  // pixel in between (12 px): a point in mid-air.
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 5.0);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < 16; ++x) disparity(x, y) = 20 * kDisparityScale;
  }
  disparity(16, 13) = 12 * kDisparityScale;
  EXPECT_EQ(removeOutliers(disparity.view(), OutlierFilterOptions{}), 1u);
  EXPECT_EQ(disparity(16, 13), kInvalidDisparity);
}

TEST(OutlierFilter, KeepsThinPoles) {
  // Poles in front of a wall (5 px): one pixel wide (20 px) and two pixels wide (15 px), rows
  // 4..22. A 1-px pole's pixel has 2*radius = 4 similar neighbours, enough; only its last two
  // pixels at each end have fewer (2, 3) and go. The 2-px pole stays whole.
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 5.0);
  for (int y = 4; y <= 22; ++y) {
    disparity(10, y) = 20 * kDisparityScale;
    disparity(20, y) = 15 * kDisparityScale;
    disparity(21, y) = 15 * kDisparityScale;
  }
  const Image<std::int16_t> before = disparity;
  EXPECT_EQ(removeOutliers(disparity.view(), OutlierFilterOptions{}), 4u);
  for (int y = 4; y <= 22; ++y) {
    const bool end = y < 6 || y > 20;
    EXPECT_EQ(disparity(10, y), end ? kInvalidDisparity : before(10, y)) << y;
    EXPECT_EQ(disparity(20, y), before(20, y)) << y;
    EXPECT_EQ(disparity(21, y), before(21, y)) << y;
  }
}

TEST(OutlierFilter, DecidesOnTheInputNotOnWhatItAlreadyRemoved) {
  // Two points side by side, each the other's only similar neighbour: both go (with
  // minNeighbours 2), whatever order the pixels are visited in; one at a time would keep neither
  // either, but a pair with minNeighbours 1 must stay.
  Image<std::int16_t> disparity(kWidth, kHeight, kInvalidDisparity);
  disparity(10, 10) = 10 * kDisparityScale;
  disparity(11, 10) = 10 * kDisparityScale;
  Image<std::int16_t> pair = disparity;
  OutlierFilterOptions one;
  one.minNeighbours = 1;
  EXPECT_EQ(removeOutliers(pair.view(), one), 0u);
  OutlierFilterOptions two;
  two.minNeighbours = 2;
  EXPECT_EQ(removeOutliers(disparity.view(), two), 2u);
}

TEST(OutlierFilter, BadOptionsAreNamed) {
  Image<std::int16_t> disparity = constantDisparity(kWidth, kHeight, 10.0);
  OutlierFilterOptions o;
  o.minNeighbours = 25;  // radius 2: 24 neighbours at most
  try {
    removeOutliers(disparity.view(), o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("minNeighbours"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lidar_sgm
