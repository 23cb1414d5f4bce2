// The per-pixel LiDAR weight of Eq. 5 (backends/common/lidar_weights.hpp): the distance to the
// scan by hand and against brute force, the weights of both alpha modes by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
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

TEST(LidarWeight, FixedAlphaIsTheSameEverywhere) {
  Parameters p;
  for (const float alpha : {0.0f, 0.7f, 1.0f}) {
    p.alpha = alpha;
    for (int d = 0; d <= kMaxLidarDistance; ++d) EXPECT_EQ(lidarWeight(p, d), alphaWeight(alpha)) << d;
  }
}

TEST(LidarWeight, AdaptiveByHand) {
  Parameters p;
  p.alphaMode = AlphaMode::Adaptive;
  // alpha 0.7: w = 179, stereo share 77, scaled by clamp(d, 1, 4) / 4 (rounded down).
  p.alpha = 0.7f;
  EXPECT_EQ(lidarWeight(p, 0), 256 - 19);  // 77 * 1 / 4 = 19
  EXPECT_EQ(lidarWeight(p, 1), 256 - 19);
  EXPECT_EQ(lidarWeight(p, 2), 256 - 38);  // 154 / 4
  EXPECT_EQ(lidarWeight(p, 3), 256 - 57);  // 231 / 4
  EXPECT_EQ(lidarWeight(p, 4), 179);
  EXPECT_EQ(lidarWeight(p, kMaxLidarDistance), 179);
  // alpha 1 stays LiDAR only; alpha 0 far from the scan stays stereo only.
  p.alpha = 1.0f;
  EXPECT_EQ(lidarWeight(p, 0), 256);
  EXPECT_EQ(lidarWeight(p, 9), 256);
  p.alpha = 0.0f;
  EXPECT_EQ(lidarWeight(p, 1), 192);
  EXPECT_EQ(lidarWeight(p, 4), 0);
}

TEST(LidarWeights, ImageFollowsTheDistanceAndTheMode) {
  const LidarPoints points(7, 5, {{1, 1, 160}, {5, 4, 320}});
  Image<std::uint16_t> distance(7, 5), weights(7, 5);
  lidarDistance(points, distance.view());
  Parameters p;
  for (const AlphaMode mode : {AlphaMode::Fixed, AlphaMode::Adaptive}) {
    p.alphaMode = mode;
    lidarWeights(points, p, weights.view());
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 7; ++x) EXPECT_EQ(weights(x, y), lidarWeight(p, distance(x, y))) << toString(mode);
    }
  }
  EXPECT_EQ(weights(1, 1), 237);  // adaptive, on the point
  EXPECT_EQ(weights(6, 0), 179);  // 4 px from both points
}

}  // namespace
}  // namespace lidar_sgm
