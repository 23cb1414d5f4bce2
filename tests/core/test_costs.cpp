// Matching costs (cpu_ref): census Hamming cost, LiDAR cost table and cost, coverage, fusion,
// and the LidarPoints container, each checked against values worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

// ---------------------------------------------------------------------------------------------
// censusCost
// ---------------------------------------------------------------------------------------------

// Left and right census rows (width 4, height 1):
//   L = {0b1011, 0xF0, 0x3FFFFFFFFFFFFFFF (62 ones), 0b1}
//   R = {0b0001, 0x0F, 0,                             0b1}
struct CensusRows {
  Image<std::uint64_t> left{4, 1};
  Image<std::uint64_t> right{4, 1};
  CensusRows() {
    left(0, 0) = 0xBull;
    left(1, 0) = 0xF0ull;
    left(2, 0) = 0x3FFFFFFFFFFFFFFFull;
    left(3, 0) = 0x1ull;
    right(0, 0) = 0x1ull;
    right(1, 0) = 0x0Full;
    right(2, 0) = 0x0ull;
    right(3, 0) = 0x1ull;
  }
};

TEST(CensusCost, HammingDistanceByHand) {
  const CensusRows rows;
  MatchingCostVolume cost(4, 1, 3);
  cpu_ref::censusCost(rows.left.view(), rows.right.view(), CensusType::Census9x7, 0, cost);
  // x=0: d=0 L0^R0 = 0b1010 -> 2; d=1,2: x-d < 0 -> 31.
  EXPECT_EQ(cost(0, 0, 0), 2);
  EXPECT_EQ(cost(0, 0, 1), kNoCounterpartCensusCost);
  EXPECT_EQ(cost(0, 0, 2), kNoCounterpartCensusCost);
  // x=1: d=0 0xF0^0x0F = 0xFF -> 8; d=1 0xF0^0x01 = 0xF1 -> 5; d=2 x-d = -1 -> 31.
  EXPECT_EQ(cost(1, 0, 0), 8);
  EXPECT_EQ(cost(1, 0, 1), 5);
  EXPECT_EQ(cost(1, 0, 2), 31);
  // x=2: d=0 62 ones ^ 0 -> 62; d=1 ^0x0F clears 4 bits -> 58; d=2 ^0x1 clears 1 bit -> 61.
  EXPECT_EQ(cost(2, 0, 0), 62);
  EXPECT_EQ(cost(2, 0, 1), 58);
  EXPECT_EQ(cost(2, 0, 2), 61);
  // x=3: d=0 1^1 -> 0; d=1 1^0 -> 1; d=2 1^0x0F = 0x0E -> 3.
  EXPECT_EQ(cost(3, 0, 0), 0);
  EXPECT_EQ(cost(3, 0, 1), 1);
  EXPECT_EQ(cost(3, 0, 2), 3);
  EXPECT_EQ(kNoCounterpartCensusCost, 31);
}

TEST(CensusCost, CenterSymmetricIsDoubled) {
  // 31-bit strings: 0b10110 ^ 0b00011 = 0b10101 -> 3 bits -> doubled 6.
  // 0x7FFFFFFF ^ 0 -> 31 bits -> 62 (both types share [0, 62]).
  Image<std::uint64_t> left(2, 1);
  Image<std::uint64_t> right(2, 1);
  left(0, 0) = 0b10110;
  left(1, 0) = 0x7FFFFFFF;
  right(0, 0) = 0b00011;
  right(1, 0) = 0;
  MatchingCostVolume cost(2, 1, 2);
  cpu_ref::censusCost(left.view(), right.view(), CensusType::CenterSymmetric9x7, 0, cost);
  EXPECT_EQ(cost(0, 0, 0), 6);
  EXPECT_EQ(cost(1, 0, 0), 62);  // L1 ^ R1 = 0x7FFFFFFF
  // L1 ^ R0 = 0x7FFFFFFF ^ 0b00011 -> 29 bits -> 58.
  EXPECT_EQ(cost(1, 0, 1), 58);
  // No counterpart is not doubled: still 31.
  EXPECT_EQ(cost(0, 0, 1), kNoCounterpartCensusCost);
}

TEST(CensusCost, PositiveMinDisparityShiftsTheRightPixel) {
  const CensusRows rows;
  MatchingCostVolume cost(4, 1, 2);
  cpu_ref::censusCost(rows.left.view(), rows.right.view(), CensusType::Census9x7, 2, cost);
  // xr = x - (2 + d).
  // x=3: d=0 -> xr=1: 1^0x0F = 0x0E -> 3; d=1 -> xr=0: 1^1 -> 0.
  EXPECT_EQ(cost(3, 0, 0), 3);
  EXPECT_EQ(cost(3, 0, 1), 0);
  // x=2: d=0 -> xr=0: 62 ones ^ 1 -> 61; d=1 -> xr=-1 -> 31.
  EXPECT_EQ(cost(2, 0, 0), 61);
  EXPECT_EQ(cost(2, 0, 1), 31);
  // x=0,1: xr < 0 for every d.
  for (int x = 0; x < 2; ++x) {
    for (int d = 0; d < 2; ++d) EXPECT_EQ(cost(x, 0, d), kNoCounterpartCensusCost) << x << "," << d;
  }
}

TEST(CensusCost, NegativeMinDisparity) {
  const CensusRows rows;
  MatchingCostVolume cost(4, 1, 3);
  cpu_ref::censusCost(rows.left.view(), rows.right.view(), CensusType::Census9x7, -1, cost);
  // Disparities -1, 0, 1: xr = x + 1 - d.
  // x=0: d=0 -> xr=1: 0b1011^0b1111 = 0b0100 -> 1; d=1 -> xr=0: 0b1010 -> 2; d=2 -> xr=-1 -> 31.
  EXPECT_EQ(cost(0, 0, 0), 1);
  EXPECT_EQ(cost(0, 0, 1), 2);
  EXPECT_EQ(cost(0, 0, 2), 31);
  // x=3: d=0 -> xr=4, right of the right image -> no counterpart 31; d=1 -> xr=3: 0;
  // d=2 -> xr=2: 1^0 -> 1.
  EXPECT_EQ(cost(3, 0, 0), kNoCounterpartCensusCost);
  EXPECT_EQ(cost(3, 0, 1), 0);
  EXPECT_EQ(cost(3, 0, 2), 1);
  // x=1: d=0 -> xr=2: 0xF0 ^ 0 -> 4.
  EXPECT_EQ(cost(1, 0, 0), 4);
}

// ---------------------------------------------------------------------------------------------
// LidarCostTable: min(cap, round(64/sigma^2 * (diff16/16)^2))
// ---------------------------------------------------------------------------------------------

TEST(LidarCostTable, SigmaTwo) {
  // 64/sigma^2 = 16: cost = 16 * (diff16/16)^2 = diff16^2 / 16.
  const LidarCostTable table(2.0f, 62);
  EXPECT_EQ(table.cap(), 62);
  EXPECT_EQ(table(0), 0);
  EXPECT_EQ(table(16), 16);   // 1 px: 16 * 1
  EXPECT_EQ(table(-16), 16);  // symmetric
  EXPECT_EQ(table(8), 4);     // 0.5 px: 16 * 0.25
  EXPECT_EQ(table(24), 36);   // 1.5 px: 16 * 2.25
  EXPECT_EQ(table(-24), 36);
  EXPECT_EQ(table(1), 0);     // 1/16 = 0.0625 -> 0
  EXPECT_EQ(table(3), 1);     // 9/16 = 0.5625 -> 1
  EXPECT_EQ(table(31), 60);   // 961/16 = 60.06 -> 60 (last entry below the cap)
  EXPECT_EQ(table(32), 62);   // 1024/16 = 64 >= 62 -> cap
  EXPECT_EQ(table(40), 62);   // 2.5 px: 100 -> cap
  EXPECT_EQ(table(-1000), 62);
  // entries() holds |diff16| = 0..31 and ends before the first value >= cap.
  ASSERT_EQ(table.entries().size(), 32u);
  EXPECT_EQ(table.entries().back(), 60);
  EXPECT_EQ(table.entries()[16], 16);
}

TEST(LidarCostTable, EntriesStopWhenCostEqualsCap) {
  // sigma 2, cap 36: diff16 = 24 costs exactly 36 = cap, so entries end at 23 (529/16 = 33.06 -> 33).
  const LidarCostTable table(2.0f, 36);
  ASSERT_EQ(table.entries().size(), 24u);
  EXPECT_EQ(table.entries().back(), 33);
  EXPECT_EQ(table(23), 33);
  EXPECT_EQ(table(24), 36);
  EXPECT_EQ(table(100), 36);
}

TEST(LidarCostTable, SigmaOne) {
  // 64/sigma^2 = 64: cost = 64 * (diff16/16)^2 = diff16^2 / 4.
  const LidarCostTable table(1.0f, 255);
  EXPECT_EQ(table(16), 64);  // 1 px
  EXPECT_EQ(table(8), 16);   // 0.5 px
  EXPECT_EQ(table(4), 4);    // 0.25 px
  EXPECT_EQ(table(2), 1);    // 4/4
  EXPECT_EQ(table(1), 0);    // 0.25 -> 0
  EXPECT_EQ(table(3), 2);    // 9/4 = 2.25 -> 2
  EXPECT_EQ(table(12), 36);  // 0.75 px: 144/4
  EXPECT_EQ(table(31), 240);  // 961/4 = 240.25 -> 240
  EXPECT_EQ(table(32), 255);  // 1024/4 = 256 >= 255 -> cap
  ASSERT_EQ(table.entries().size(), 32u);
  EXPECT_EQ(table.entries().back(), 240);

  const LidarCostTable capped(1.0f, 62);
  // 15^2/4 = 56.25 -> 56 < 62; 16^2/4 = 64 >= 62.
  ASSERT_EQ(capped.entries().size(), 16u);
  EXPECT_EQ(capped.entries().back(), 56);
  EXPECT_EQ(capped(16), 62);
}

// ---------------------------------------------------------------------------------------------
// lidarCost: min over the points of the pixel and its 8 neighbours of table(16*(min+d) - dP16)
// ---------------------------------------------------------------------------------------------

// Costs with sigma 2, cap 62 (table(k) = min(62, k^2/16)), D = 5, minDisparity 0:
//   point A, 2.5 px (40): diff16 = 16d - 40 = -40,-24,-8,8,24 -> 62(100 capped),36,4,4,36
//   point B, 4 px   (64): diff16 = -64,-48,-32,-16,0        -> 62,62,62(64 capped),16,0
//   point C, 1 px   (16): diff16 = -16,0,16,32,48           -> 16,0,16,62(64),62(144)
constexpr int kA = 40;
constexpr int kB = 64;
constexpr int kC = 16;

void expectCosts(const MatchingCostVolume& cost, int x, int y, const std::vector<int>& expected) {
  for (int d = 0; d < static_cast<int>(expected.size()); ++d) {
    EXPECT_EQ(cost(x, y, d), expected[static_cast<std::size_t>(d)]) << "pixel " << x << "," << y << " d " << d;
  }
}

TEST(LidarCost, OnePoint) {
  const LidarPoints points(6, 4, {{1, 1, kA}});
  const LidarCostTable table(2.0f, 62);
  MatchingCostVolume cost(6, 4, 5);
  Image<std::uint8_t> support(6, 4, 7);
  cpu_ref::lidarCost(points, table, 0, cost, support.view());
  // The point's pixel and its 8 neighbours (x 0..2, y 0..2) get A's costs, support 1.
  for (int y = 0; y <= 2; ++y) {
    for (int x = 0; x <= 2; ++x) {
      expectCosts(cost, x, y, {62, 36, 4, 4, 36});
      EXPECT_EQ(support(x, y), 1) << x << "," << y;
    }
  }
  // (3,1) is 2 columns away, (1,3) 2 rows away: no information, cost 0 for all d, support 0.
  expectCosts(cost, 3, 1, {0, 0, 0, 0, 0});
  expectCosts(cost, 1, 3, {0, 0, 0, 0, 0});
  expectCosts(cost, 5, 3, {0, 0, 0, 0, 0});
  EXPECT_EQ(support(3, 1), 0);
  EXPECT_EQ(support(1, 3), 0);
  EXPECT_EQ(support(3, 3), 0);
  EXPECT_EQ(support(5, 0), 0);
}

TEST(LidarCost, MinimumOverPointsOfOnePixel) {
  // A and B both in pixel (1,1): min(A, B) = 62, 36, 4, 4, 0 (B wins at d = 4).
  const LidarPoints points(6, 4, {{1, 1, kA}, {1, 1, kB}});
  const LidarCostTable table(2.0f, 62);
  MatchingCostVolume cost(6, 4, 5);
  Image<std::uint8_t> support(6, 4);
  cpu_ref::lidarCost(points, table, 0, cost, support.view());
  expectCosts(cost, 1, 1, {62, 36, 4, 4, 0});
  expectCosts(cost, 0, 0, {62, 36, 4, 4, 0});
  expectCosts(cost, 2, 2, {62, 36, 4, 4, 0});
}

TEST(LidarCost, MinimumOverNeighbouringPixels) {
  // A and B in (1,1), C in (2,1).
  const LidarPoints points(6, 4, {{1, 1, kA}, {1, 1, kB}, {2, 1, kC}});
  const LidarCostTable table(2.0f, 62);
  MatchingCostVolume cost(6, 4, 5);
  Image<std::uint8_t> support(6, 4);
  cpu_ref::lidarCost(points, table, 0, cost, support.view());
  // (1,1) and (2,0) see A, B, C: min = 16, 0, 4, 4, 0.
  expectCosts(cost, 1, 1, {16, 0, 4, 4, 0});
  expectCosts(cost, 2, 0, {16, 0, 4, 4, 0});
  // (0,1) sees A, B only (C is 2 columns away): 62, 36, 4, 4, 0.
  expectCosts(cost, 0, 1, {62, 36, 4, 4, 0});
  // (3,2) sees C only ((1,1) is 2 columns away): 16, 0, 16, 62, 62.
  expectCosts(cost, 3, 2, {16, 0, 16, 62, 62});
  // (4,1) is 2 columns from C: nothing.
  expectCosts(cost, 4, 1, {0, 0, 0, 0, 0});
  EXPECT_EQ(support(3, 1), 1);
  EXPECT_EQ(support(4, 1), 0);
  EXPECT_EQ(support(0, 3), 0);
}

TEST(LidarCost, MinDisparityAndEmptySupport) {
  // minDisparity 2: candidate disparity16 = 16*(2 + d) = 32, 48, 64; point A (40):
  // diff16 = -8, 8, 24 -> 4, 4, 36.
  const LidarPoints points(3, 3, {{1, 1, kA}});
  const LidarCostTable table(2.0f, 62);
  MatchingCostVolume cost(3, 3, 3);
  cpu_ref::lidarCost(points, table, 2, cost, ImageView<std::uint8_t>());  // support may be empty
  expectCosts(cost, 0, 2, {4, 4, 36});
  // minDisparity -1: 16*(-1 + d) = -16, 0, 16; diff16 = -56, -40, -24 -> 62 (196), 62 (100), 36.
  cpu_ref::lidarCost(points, table, -1, cost, ImageView<std::uint8_t>());
  expectCosts(cost, 2, 2, {62, 62, 36});
}

TEST(LidarCoverage, ColumnsAndRows) {
  // 5x8 image, one point at (2,4): covered iff |x-2| <= 1 and |y-4| <= rows.
  const LidarPoints points(5, 8, {{2, 4, 32}});
  Image<std::uint8_t> coverage(5, 8, 9);
  cpu_ref::lidarCoverage(points, 2, coverage.view());
  const std::uint8_t expectedRows2[8][5] = {
      {0, 0, 0, 0, 0},  // y=0
      {0, 0, 0, 0, 0},  // y=1
      {0, 1, 1, 1, 0},  // y=2
      {0, 1, 1, 1, 0},  // y=3
      {0, 1, 1, 1, 0},  // y=4 (the point)
      {0, 1, 1, 1, 0},  // y=5
      {0, 1, 1, 1, 0},  // y=6
      {0, 0, 0, 0, 0},  // y=7
  };
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 5; ++x) EXPECT_EQ(coverage(x, y), expectedRows2[y][x]) << x << "," << y;
  }
  cpu_ref::lidarCoverage(points, 1, coverage.view());
  EXPECT_EQ(coverage(2, 2), 0);
  EXPECT_EQ(coverage(2, 3), 1);
  EXPECT_EQ(coverage(3, 5), 1);
  EXPECT_EQ(coverage(1, 6), 0);
  EXPECT_EQ(coverage(4, 4), 0);
  // rows 6 reaches y = -2..10: every row of columns 1..3, never columns 0 or 4.
  cpu_ref::lidarCoverage(points, 6, coverage.view());
  EXPECT_EQ(coverage(1, 0), 1);
  EXPECT_EQ(coverage(3, 7), 1);
  EXPECT_EQ(coverage(0, 4), 0);
  EXPECT_EQ(coverage(4, 0), 0);
}

// ---------------------------------------------------------------------------------------------
// fuseCosts: (w*C_L + (256-w)*C_S + 128) >> 8
// ---------------------------------------------------------------------------------------------

TEST(FuseCosts, AlphaWeight) {
  EXPECT_EQ(alphaWeight(0.7f), 179);  // 0.7*256 = 179.2 -> 179
  EXPECT_EQ(alphaWeight(0.0f), 0);
  EXPECT_EQ(alphaWeight(0.5f), 128);
  EXPECT_EQ(alphaWeight(1.0f), 256);
}

struct FusionInput {
  // 2x1 volume, D = 4: pixel 0 has support 1, pixel 1 support 0; same costs at both pixels.
  //   C_L = 62, 0, 36, 4;  C_S = 0, 62, 20, 31
  MatchingCostVolume lidar{2, 1, 4};
  MatchingCostVolume stereo{2, 1, 4};
  Image<std::uint8_t> support{2, 1};
  FusionInput() {
    const std::uint8_t cL[4] = {62, 0, 36, 4};
    const std::uint8_t cS[4] = {0, 62, 20, 31};
    for (int x = 0; x < 2; ++x) {
      for (int d = 0; d < 4; ++d) {
        lidar(x, 0, d) = cL[d];
        stereo(x, 0, d) = cS[d];
      }
    }
    support(0, 0) = 1;
    support(1, 0) = 0;
  }
};

TEST(FuseCosts, ByHandAlpha07) {
  const FusionInput in;
  MatchingCostVolume fused(2, 1, 4);
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), 179, false, fused);
  // (179*62 + 77*0 + 128) >> 8 = 11226 >> 8 = 43
  // (179*0 + 77*62 + 128) >> 8 = 4902 >> 8 = 19
  // (179*36 + 77*20 + 128) >> 8 = (6444 + 1540 + 128) >> 8 = 8112 >> 8 = 31
  // (179*4 + 77*31 + 128) >> 8 = (716 + 2387 + 128) >> 8 = 3231 >> 8 = 12
  // Without stereoCostWithoutLidar the support does not matter.
  for (int x = 0; x < 2; ++x) expectCosts(fused, x, 0, {43, 19, 31, 12});
}

TEST(FuseCosts, AlphaZeroAndOne) {
  const FusionInput in;
  MatchingCostVolume fused(2, 1, 4);
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), alphaWeight(0.0f), false, fused);
  expectCosts(fused, 0, 0, {0, 62, 20, 31});  // (256*C_S + 128) >> 8 = C_S
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), alphaWeight(1.0f), false, fused);
  expectCosts(fused, 1, 0, {62, 0, 36, 4});   // (256*C_L + 128) >> 8 = C_L
}

TEST(FuseCosts, StereoCostWithoutLidarKeepsStereoWhereNoSupport) {
  const FusionInput in;
  MatchingCostVolume fused(2, 1, 4);
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), 179, true, fused);
  expectCosts(fused, 0, 0, {43, 19, 31, 12});  // support 1: fused
  expectCosts(fused, 1, 0, {0, 62, 20, 31});   // support 0: C_S unchanged
}

TEST(FuseCosts, PerPixelWeights) {
  const FusionInput in;
  Image<std::uint16_t> weights(2, 1);
  weights(0, 0) = 179;  // the paper's alpha at pixel 0 ...
  weights(1, 0) = 237;  // ... more LiDAR at pixel 1
  MatchingCostVolume fused(2, 1, 4);
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), std::as_const(weights).view(), false, fused);
  expectCosts(fused, 0, 0, {43, 19, 31, 12});  // as ByHandAlpha07
  // (237*62 + 128) >> 8 = 14822 >> 8 = 57;  (19*62 + 128) >> 8 = 1306 >> 8 = 5
  // (237*36 + 19*20 + 128) >> 8 = (8532 + 380 + 128) >> 8 = 9040 >> 8 = 35
  // (237*4 + 19*31 + 128) >> 8 = (948 + 589 + 128) >> 8 = 1665 >> 8 = 6
  expectCosts(fused, 1, 0, {57, 5, 35, 6});
  // With stereoCostWithoutLidar, pixel 1 (support 0) keeps C_S whatever its weight.
  cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), std::as_const(weights).view(), true, fused);
  expectCosts(fused, 1, 0, {0, 62, 20, 31});
}

TEST(FuseCosts, OneWeightIsAConstantWeightImage) {
  const FusionInput in;
  for (const int w : {0, 1, 179, 255, 256}) {
    const Image<std::uint16_t> weights(2, 1, static_cast<std::uint16_t>(w));
    for (const bool stereoWithoutLidar : {false, true}) {
      MatchingCostVolume byImage(2, 1, 4), byWeight(2, 1, 4);
      cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), weights.view(), stereoWithoutLidar, byImage);
      cpu_ref::fuseCosts(in.lidar, in.stereo, in.support.view(), w, stereoWithoutLidar, byWeight);
      for (int x = 0; x < 2; ++x) {
        for (int d = 0; d < 4; ++d) EXPECT_EQ(byImage(x, 0, d), byWeight(x, 0, d)) << "w " << w;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// LidarPoints
// ---------------------------------------------------------------------------------------------

TEST(LidarPoints, BucketsKeepAllPointsInOrder) {
  const LidarPoints points(3, 2, {{1, 0, 16}, {2, 1, 32}, {1, 0, 48}, {1, 0, 20}});
  EXPECT_EQ(points.width(), 3);
  EXPECT_EQ(points.height(), 2);
  EXPECT_EQ(points.size(), 4u);
  EXPECT_FALSE(points.empty());
  ASSERT_EQ(points.count(1, 0), 3);
  EXPECT_EQ(std::vector<int>(points.begin(1, 0), points.end(1, 0)), (std::vector<int>{16, 48, 20}));
  ASSERT_EQ(points.count(2, 1), 1);
  EXPECT_EQ(*points.begin(2, 1), 32);
  EXPECT_EQ(points.count(0, 0), 0);
  EXPECT_EQ(points.count(2, 0), 0);
  EXPECT_EQ(points.count(0, 1), 0);
  EXPECT_EQ(points.count(1, 1), 0);
}

// pointPixels() with pixelStarts(): what a backend rebuilds the compressed rows from (a lower
// bound of each pixel among the points' pixels gives its first point).
TEST(LidarPoints, PointPixelsNameEachPointsPixelInTheCompressedOrder) {
  const LidarPoints points(3, 2, {{1, 0, 16}, {2, 1, 32}, {1, 0, 48}, {0, 1, 20}});
  EXPECT_EQ(points.pointPixels(), (std::vector<int>{1, 1, 3, 5}));
  EXPECT_EQ(points.disparities16(), (std::vector<int>{16, 48, 20, 32}));
  const auto& starts = points.pixelStarts();
  const std::vector<int>& pixels = points.pointPixels();
  for (int p = 0; p <= 6; ++p) {
    const auto first = std::lower_bound(pixels.begin(), pixels.end(), p) - pixels.begin();
    EXPECT_EQ(starts[static_cast<std::size_t>(p)], first) << "pixel " << p;
  }
}

// A pipeline rebuilds its points every frame: assign() gives what construction gives and keeps
// the pixel offsets' memory; a refused sample list leaves the object empty, not half-built.
TEST(LidarPoints, AssignReusesItsBuffersAndEqualsConstruction) {
  LidarPoints points(3, 2, {{1, 0, 16}, {2, 1, 32}});
  const int* offsets = points.pixelStarts().data();
  const std::vector<LidarSample> next = {{0, 1, 20}, {1, 0, 48}, {0, 1, 24}};
  points.assign(3, 2, next);
  const LidarPoints built(3, 2, next);
  EXPECT_EQ(points.pixelStarts().data(), offsets);
  EXPECT_EQ(std::vector<int>(points.pixelStarts().begin(), points.pixelStarts().end()),
            std::vector<int>(built.pixelStarts().begin(), built.pixelStarts().end()));
  EXPECT_EQ(points.disparities16(), (std::vector<int>{48, 20, 24}));
  EXPECT_EQ(points.pointPixels(), built.pointPixels());
  EXPECT_EQ(std::vector<int>(points.begin(0, 1), points.end(0, 1)), (std::vector<int>{20, 24}));
  EXPECT_EQ(points.count(2, 1), 0);
  EXPECT_THROW(points.assign(3, 2, {{0, 0, 16}, {5, 0, 16}}), std::invalid_argument);
  EXPECT_TRUE(points.empty());
  EXPECT_EQ(points.width(), 0);
}

TEST(LidarPoints, EmptySampleList) {
  const LidarPoints points(4, 3, {});
  EXPECT_TRUE(points.empty());
  EXPECT_EQ(points.size(), 0u);
  EXPECT_EQ(points.count(3, 2), 0);
}

std::string constructionError(int width, int height, const std::vector<LidarSample>& samples) {
  try {
    const LidarPoints points(width, height, samples);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(LidarPoints, RejectsPointOutsideImage) {
  EXPECT_THROW(LidarPoints(3, 2, {{3, 0, 16}}), std::invalid_argument);
  EXPECT_THROW(LidarPoints(3, 2, {{0, 2, 16}}), std::invalid_argument);
  EXPECT_THROW(LidarPoints(3, 2, {{-1, 0, 16}}), std::invalid_argument);
  EXPECT_THROW(LidarPoints(3, 2, {{0, -1, 16}}), std::invalid_argument);
  const std::string message = constructionError(3, 2, {{0, 0, 16}, {3, 1, 16}});
  EXPECT_NE(message.find("outside"), std::string::npos) << message;
  EXPECT_NE(message.find("point 1"), std::string::npos) << message;  // names the offending sample
}

TEST(LidarPoints, RejectsNonPositiveDisparity) {
  EXPECT_THROW(LidarPoints(3, 2, {{1, 1, 0}}), std::invalid_argument);
  const std::string message = constructionError(3, 2, {{1, 1, -5}});
  EXPECT_NE(message.find("behind"), std::string::npos) << message;
}

TEST(LidarPoints, RejectsEmptyImage) {
  EXPECT_THROW(LidarPoints(0, 2, {}), std::invalid_argument);
}

TEST(LidarPoints, FromDisparityImageSkipsInvalid) {
  // 3x2:  INV  16   0
  //       -32  40  INV
  // Only the positive values become points: (1,0) = 16 and (1,1) = 40.
  Image<std::int16_t> sparse(3, 2);
  sparse(0, 0) = kInvalidDisparity;
  sparse(1, 0) = 16;
  sparse(2, 0) = 0;
  sparse(0, 1) = -32;
  sparse(1, 1) = 40;
  sparse(2, 1) = kInvalidDisparity;
  const LidarPoints points = LidarPoints::fromDisparityImage(sparse.view());
  EXPECT_EQ(points.width(), 3);
  EXPECT_EQ(points.height(), 2);
  EXPECT_EQ(points.size(), 2u);
  ASSERT_EQ(points.count(1, 0), 1);
  EXPECT_EQ(*points.begin(1, 0), 16);
  ASSERT_EQ(points.count(1, 1), 1);
  EXPECT_EQ(*points.begin(1, 1), 40);
  EXPECT_EQ(points.count(0, 0), 0);
  EXPECT_EQ(points.count(2, 0), 0);
  EXPECT_EQ(points.count(0, 1), 0);
}

}  // namespace
}  // namespace lidar_sgm
