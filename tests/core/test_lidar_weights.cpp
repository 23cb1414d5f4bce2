// The per-pixel LiDAR weight of Eq. 5 (backends/common/lidar_weights.hpp): the distance to the
// scan by hand and against brute force, the weights of both alpha modes by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "backends/common/lidar_weights.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

TEST(LidarDistance, ChessboardDistanceByHand) {
  // 7x5, points at (1, 1) and (5, 4): d = min(max(|x-1|, |y-1|), max(|x-5|, |y-4|)).
  const LidarPoints points(7, 5, {{1, 1, 160}, {5, 4, 320}});
  Image<std::uint16_t> distance(7, 5);
  lidarDistance(points, distance.view());
  const int expected[5][7] = {{1, 1, 1, 2, 3, 4, 4},
                              {1, 0, 1, 2, 3, 3, 3},
                              {1, 1, 1, 2, 2, 2, 2},
                              {2, 2, 2, 2, 1, 1, 1},
                              {3, 3, 3, 2, 1, 0, 1}};
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) EXPECT_EQ(distance(x, y), expected[y][x]) << "(" << x << ", " << y << ")";
  }
}

TEST(LidarDistance, MatchesBruteForceOnAnOddSizeAndCapsFarPixels) {
  // Scan-like rows (every 5th row, 3 of 4 columns) in the lower half of a 301x83 image, nothing
  // above row 40.
  const int width = 301, height = 83;
  std::mt19937 engine(5);
  std::vector<LidarSample> samples;
  for (int y = 40; y < height; y += 5) {
    for (int x = 0; x < width; ++x) {
      if (engine() % 4u != 0) samples.push_back({x, y, 16 + static_cast<int>(engine() % 800u)});
    }
  }
  const LidarPoints points(width, height, samples);
  Image<std::uint16_t> distance(width, height);
  lidarDistance(points, distance.view());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int best = kMaxLidarDistance;
      for (const LidarSample& s : samples) best = std::min(best, std::max(std::abs(s.x - x), std::abs(s.y - y)));
      ASSERT_EQ(distance(x, y), best) << "(" << x << ", " << y << ")";
    }
  }
  // No point, or none within the cap: kMaxLidarDistance.
  const LidarPoints far(600, 3, {{0, 0, 16}});
  Image<std::uint16_t> farDistance(600, 3);
  lidarDistance(far, farDistance.view());
  EXPECT_EQ(farDistance(254, 2), 254);
  EXPECT_EQ(farDistance(255, 0), kMaxLidarDistance);
  EXPECT_EQ(farDistance(599, 1), kMaxLidarDistance);
}

TEST(LidarDistance, RejectsAnImageOfAnotherSize) {
  const LidarPoints points(7, 5, {{1, 1, 160}});
  Image<std::uint16_t> distance(7, 4);
  EXPECT_THROW(lidarDistance(points, distance.view()), std::invalid_argument);
}

TEST(LidarDensity, ShareOfTheScanAreaNearAPointByHand) {
  // The 7x5 frame of ChessboardDistanceByHand: 15 of its 35 pixels (all within 8 px) are within
  // 1 px of a point: rho = 15 * 256 / 35 = 109 (rounded down).
  const LidarPoints points(7, 5, {{1, 1, 160}, {5, 4, 320}});
  Image<std::uint16_t> distance(7, 5);
  lidarDistance(points, distance.view());
  EXPECT_EQ(lidarDensity256(std::as_const(distance).view()), 109);
  // No point at all: no scan area, density 0.
  const Image<std::uint16_t> empty(4, 3, static_cast<std::uint16_t>(kMaxLidarDistance));
  EXPECT_EQ(lidarDensity256(empty.view()), 0);
}

TEST(LidarDensity, FactorFallsFromOneToAQuarterBetweenSparseAndDense) {
  EXPECT_EQ(densityFactor256(0), 256);
  EXPECT_EQ(densityFactor256(kSparseDensity256), 256);
  EXPECT_EQ(densityFactor256(109), 238);  // (204 - 109) * 256 / 102 = 238.4
  EXPECT_EQ(densityFactor256(153), 128);  // halfway
  EXPECT_EQ(densityFactor256(kDenseDensity256), 64);
  EXPECT_EQ(densityFactor256(256), 64);
}

TEST(LidarWeight, FixedAlphaIsTheSameEverywhere) {
  Parameters p;
  for (const float alpha : {0.0f, 0.7f, 1.0f}) {
    p.alpha = alpha;
    for (int d = 0; d <= kMaxLidarDistance; ++d) {
      for (const int factor : {64, 128, 256}) EXPECT_EQ(lidarWeight(p, d, factor), alphaWeight(alpha)) << d;
    }
  }
}

TEST(LidarWeight, AdaptiveByHand) {
  Parameters p;
  p.alphaMode = AlphaMode::Adaptive;
  // alpha 0.7: w = 179, stereo share 77, scaled by clamp(d, 1, 8) / 8 and the density factor.
  p.alpha = 0.7f;
  EXPECT_EQ(lidarWeight(p, 0, 256), 256 - 9);   // 77 / 8 = 9.6
  EXPECT_EQ(lidarWeight(p, 1, 256), 256 - 9);
  EXPECT_EQ(lidarWeight(p, 2, 256), 256 - 19);  // 154 / 8
  EXPECT_EQ(lidarWeight(p, 4, 256), 256 - 38);  // 308 / 8
  EXPECT_EQ(lidarWeight(p, 8, 256), 179);       // a sparse scan, far: the fixed alpha
  EXPECT_EQ(lidarWeight(p, kMaxLidarDistance, 256), 179);
  EXPECT_EQ(lidarWeight(p, 1, 64), 256 - 2);    // a dense scan: 77 / 32 = 2.4
  EXPECT_EQ(lidarWeight(p, 8, 64), 256 - 19);   // 616 / 32 = 19.25
  EXPECT_EQ(lidarWeight(p, 8, 128), 256 - 38);  // 1232 / 32 = 38.5
  // alpha 1 stays LiDAR only; alpha 0 far from a sparse scan stays stereo only.
  p.alpha = 1.0f;
  EXPECT_EQ(lidarWeight(p, 0, 64), 256);
  EXPECT_EQ(lidarWeight(p, 9, 256), 256);
  p.alpha = 0.0f;
  EXPECT_EQ(lidarWeight(p, 1, 256), 256 - 32);
  EXPECT_EQ(lidarWeight(p, 8, 256), 0);
}

TEST(LidarWeights, NoPointGivesTheFixedAlphaEverywhere) {
  const LidarPoints none(5, 3, {});
  Image<std::uint16_t> weights(5, 3);
  Parameters p;
  p.alphaMode = AlphaMode::Adaptive;
  lidarWeights(none, p, weights.view());
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) EXPECT_EQ(weights(x, y), alphaWeight(p.alpha));
  }
}

TEST(LidarWeights, ImageFollowsTheDistanceTheDensityAndTheMode) {
  const LidarPoints points(7, 5, {{1, 1, 160}, {5, 4, 320}});
  Image<std::uint16_t> distance(7, 5), weights(7, 5);
  lidarDistance(points, distance.view());
  Parameters p;
  for (const AlphaMode mode : {AlphaMode::Fixed, AlphaMode::Adaptive}) {
    p.alphaMode = mode;
    lidarWeights(points, p, weights.view());
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 7; ++x) EXPECT_EQ(weights(x, y), lidarWeight(p, distance(x, y), 238)) << toString(mode);
    }
  }
  EXPECT_EQ(weights(1, 1), 256 - 8);   // on the point: 77 * 1 * 238 / 2048 = 8.9
  EXPECT_EQ(weights(6, 0), 256 - 35);  // 4 px from both points: 77 * 4 * 238 / 2048 = 35.8
}

}  // namespace
}  // namespace lidar_sgm
