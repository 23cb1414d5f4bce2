// SGM aggregation (cpu_ref, Eq. 1), checked against path costs worked out by hand.
//
// Eq. 1: L(p,d) = C(p,d) + min(L(p-r,d), L(p-r,d-1)+P1, L(p-r,d+1)+P1, min_i L(p-r,i)+P2)
//                 - min_k L(p-r,k);  L = C where the path starts.
// Directions, in the order paths 0..7 use them: (1,0) (-1,0) (0,1) (0,-1) then the diagonals
// (1,1) (-1,1) (1,-1) (-1,-1); p - r is the previous pixel on the path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

// ---------------------------------------------------------------------------------------------
// pathCostStep
// ---------------------------------------------------------------------------------------------

TEST(PathCostStep, EachTermWins) {
  // previous = {20, 10, 30, 45, 12}, min = 10, P1 = 5, P2 = 20 (min + P2 = 30), C = 7.
  const std::uint16_t previous[5] = {20, 10, 30, 45, 12};
  const int P1 = 5;
  const int P2 = 20;
  // d=1: same d wins: min(10, 20+5, 30+5, 30) = 10 -> 7 + 10 - 10 = 7.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 5, 1, 10, P1, P2), 7);
  // d=2: d-1 + P1 wins: min(30, 10+5, 45+5, 30) = 15 -> 7 + 15 - 10 = 12.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 5, 2, 10, P1, P2), 12);
  // d=3: d+1 + P1 wins: min(45, 30+5, 12+5, 30) = 17 -> 7 + 17 - 10 = 14.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 5, 3, 10, P1, P2), 14);
  // d=0 (boundary, no d-1): d+1 + P1 wins: min(20, 10+5, 30) = 15 -> 12.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 5, 0, 10, P1, P2), 12);
  // d=4 (boundary, no d+1): min(12, 45+5, 30) = 12 -> 7 + 12 - 10 = 9.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 5, 4, 10, P1, P2), 9);

  // min + P2 wins: previous = {10, 60, 80, 60, 50}, d=2: min(80, 60+5, 60+5, 10+20) = 30
  // -> 7 + 30 - 10 = 27.
  const std::uint16_t far[5] = {10, 60, 80, 60, 50};
  EXPECT_EQ(cpu_ref::pathCostStep(7, far, 5, 2, 10, P1, P2), 27);
  // d=1 there: min(60, 10+5, 80+5, 30) = 15 -> 7 + 5 = 12 (d-1 beats P2).
  EXPECT_EQ(cpu_ref::pathCostStep(7, far, 5, 1, 10, P1, P2), 12);
}

TEST(PathCostStep, BoundariesDoNotReadOutsideTheRange) {
  // The previous costs of D = 4 sit between two 0 sentinels; reading previous[-1] or
  // previous[D] would find 0 + P1 = 5 and lower the result.
  const std::uint16_t buffer[6] = {0, 40, 50, 45, 60, 0};
  const std::uint16_t* previous = buffer + 1;  // {40, 50, 45, 60}, min 40
  // d=0: min(40, 50+5, 40+20) = 40 -> 3 + 40 - 40 = 3.
  EXPECT_EQ(cpu_ref::pathCostStep(3, previous, 4, 0, 40, 5, 20), 3);
  // d=3: min(60, 45+5, 60) = 50 -> 3 + 50 - 40 = 13.
  EXPECT_EQ(cpu_ref::pathCostStep(3, previous, 4, 3, 40, 5, 20), 13);
}

TEST(PathCostStep, SingleDisparity) {
  // D = 1: only L(p-r, 0) and min + P2: min(9, 9+20) = 9 -> 4 + 9 - 9 = 4.
  const std::uint16_t previous[1] = {9};
  EXPECT_EQ(cpu_ref::pathCostStep(4, previous, 1, 0, 9, 5, 20), 4);
}

// ---------------------------------------------------------------------------------------------
// aggregatePaths
// ---------------------------------------------------------------------------------------------

void setCosts(MatchingCostVolume& cost, int x, int y, const std::vector<int>& values) {
  for (int d = 0; d < static_cast<int>(values.size()); ++d) {
    cost(x, y, d) = static_cast<std::uint8_t>(values[static_cast<std::size_t>(d)]);
  }
}

void expectSums(const AggregatedCostVolume& sum, int x, int y, const std::vector<int>& expected) {
  for (int d = 0; d < static_cast<int>(expected.size()); ++d) {
    EXPECT_EQ(sum(x, y, d), expected[static_cast<std::size_t>(d)]) << "pixel " << x << "," << y << " d " << d;
  }
}

TEST(AggregatePaths, FourPathsOnARow) {
  // 3x1, D = 3, P1 = 2, P2 = 5.  C(0) = {0,4,8}, C(1) = {6,2,7}, C(2) = {9,9,0}.
  MatchingCostVolume cost(3, 1, 3);
  setCosts(cost, 0, 0, {0, 4, 8});
  setCosts(cost, 1, 0, {6, 2, 7});
  setCosts(cost, 2, 0, {9, 9, 0});
  // Left to right: L(0) = {0,4,8} (min 0).
  //   L(1): d0 min(0, 4+2, 0+5) = 0 -> 6;  d1 min(4, 0+2, 8+2, 5) = 2 -> 4;
  //         d2 min(8, 4+2, 5) = 5 -> 12.                          L(1) = {6,4,12} (min 4)
  //   L(2): d0 min(6, 4+2, 4+5) = 6 -> 9+6-4 = 11;  d1 min(4, ...) = 4 -> 9;
  //         d2 min(12, 4+2, 9) = 6 -> 0+6-4 = 2.                  L(2) = {11,9,2}
  // Right to left: L(2) = {9,9,0} (min 0).
  //   L(1): d0 min(9, 9+2, 5) = 5 -> 11;  d1 min(9, 11, 0+2, 5) = 2 -> 4;  d2 min(0, ...) = 0 -> 7.
  //                                                               L(1) = {11,4,7} (min 4)
  //   L(0): d0 min(11, 4+2, 9) = 6 -> 0+6-4 = 2;  d1 min(4, ...) = 4 -> 4;
  //         d2 min(7, 4+2, 9) = 6 -> 8+6-4 = 10.                  L(0) = {2,4,10}
  // Up and down: height 1, every path starts at once: L = C, counted twice.
  // Sum = LR + RL + 2C:
  //   x0: {0+2+0, 4+4+8, 8+10+16} = {2, 16, 34}
  //   x1: {6+11+12, 4+4+4, 12+7+14} = {29, 12, 33}
  //   x2: {11+9+18, 9+9+18, 2+0+0} = {38, 36, 2}
  AggregatedCostVolume sum(3, 1, 3);
  cpu_ref::aggregatePaths(cost, 2, 5, 4, sum);
  expectSums(sum, 0, 0, {2, 16, 34});
  expectSums(sum, 1, 0, {29, 12, 33});
  expectSums(sum, 2, 0, {38, 36, 2});
}

// 2x2, D = 3, P1 = 2, P2 = 6:
//   a = (0,0): {0,3,9}   b = (1,0): {7,1,4}
//   c = (0,1): {2,8,0}   e = (1,1): {5,5,2}
MatchingCostVolume squareCosts() {
  MatchingCostVolume cost(2, 2, 3);
  setCosts(cost, 0, 0, {0, 3, 9});
  setCosts(cost, 1, 0, {7, 1, 4});
  setCosts(cost, 0, 1, {2, 8, 0});
  setCosts(cost, 1, 1, {5, 5, 2});
  return cost;
}

// Every path on the 2x2 image has at most 2 pixels; the one step from each start:
//   (1,0)   b from a (min 0): d0 min(0,5,6)=0 -> 7;  d1 min(3,2,11,6)=2 -> 3;  d2 min(9,5,6)=5 -> 9
//           e from c (min 0): d0 min(2,10,6)=2 -> 7; d1 min(8,4,2,6)=2 -> 7;  d2 min(0,..)=0 -> 2
//   (-1,0)  a from b (min 1): d0 min(7,3,7)=3 -> 2;  d1 1 -> 3;               d2 min(4,3,7)=3 -> 11
//           c from e (min 2): d0 min(5,7,8)=5 -> 5;  d1 min(5,7,4,8)=4 -> 10; d2 2 -> 0
//   (0,1)   c from a (min 0): d0 0 -> 2;             d1 2 -> 10;              d2 5 -> 5
//           e from b (min 1): d0 3 -> 7;             d1 1 -> 5;               d2 3 -> 4
//   (0,-1)  a from c (min 0): d0 min(2,10,6)=2 -> 2; d1 min(8,4,2,6)=2 -> 5;  d2 0 -> 9
//           b from e (min 2): d0 5 -> 10;            d1 4 -> 3;               d2 2 -> 4
// 4-path sums (starting pixels contribute C):
//   a: C{0,3,9} + RL{2,3,11} + C{0,3,9} + BT{2,5,9}  = {4, 14, 38}
//   b: LR{7,3,9} + C{7,1,4} + C{7,1,4} + BT{10,3,4}  = {31, 8, 21}
//   c: C{2,8,0} + RL{5,10,0} + TB{2,10,5} + C{2,8,0} = {11, 36, 5}
//   e: LR{7,7,2} + C{5,5,2} + TB{7,5,4} + C{5,5,2}   = {24, 22, 10}
TEST(AggregatePaths, FourPathsOnASquare) {
  const MatchingCostVolume cost = squareCosts();
  AggregatedCostVolume sum(2, 2, 3);
  cpu_ref::aggregatePaths(cost, 2, 6, 4, sum);
  expectSums(sum, 0, 0, {4, 14, 38});
  expectSums(sum, 1, 0, {31, 8, 21});
  expectSums(sum, 0, 1, {11, 36, 5});
  expectSums(sum, 1, 1, {24, 22, 10});
}

TEST(AggregatePaths, EightPathsOnASquare) {
  // Diagonals: each has one 2-pixel path, the other pixels start (contribute C).
  //   (1,1)   e from a (min 0): d0 min(0,5,6)=0 -> 5;  d1 min(3,2,11,6)=2 -> 7;  d2 min(9,5,6)=5 -> 7
  //   (-1,1)  c from b (min 1): d0 min(7,3,7)=3 -> 4;  d1 1 -> 8;               d2 min(4,3,7)=3 -> 2
  //   (1,-1)  b from c (min 0): d0 min(2,10,6)=2 -> 9; d1 min(8,4,2,6)=2 -> 3;  d2 0 -> 4
  //   (-1,-1) a from e (min 2): d0 min(5,7,8)=5 -> 3;  d1 min(5,7,4,8)=4 -> 5;  d2 2 -> 9
  // Diagonal sums:
  //   a: C + C + C + {3,5,9}        = {3, 14, 36}
  //   b: C + C + {9,3,4} + C        = {30, 6, 16}
  //   c: C + {4,8,2} + C + C        = {10, 32, 2}
  //   e: {5,7,7} + C + C + C        = {20, 22, 13}
  // 8-path sums = 4-path sums + diagonal sums:
  //   a {7, 28, 74}  b {61, 14, 37}  c {21, 68, 7}  e {44, 44, 23}
  const MatchingCostVolume cost = squareCosts();
  AggregatedCostVolume sum(2, 2, 3);
  cpu_ref::aggregatePaths(cost, 2, 6, 8, sum);
  expectSums(sum, 0, 0, {7, 28, 74});
  expectSums(sum, 1, 0, {61, 14, 37});
  expectSums(sum, 0, 1, {21, 68, 7});
  expectSums(sum, 1, 1, {44, 44, 23});
}

TEST(AggregatePaths, ConstantCostGivesPathsTimesCost) {
  // All C = 7: every step sees previous = {7,...} (min 7), keeps 7: L = 7 + 7 - 7 = 7 everywhere,
  // so S = paths * 7. The output is overwritten, not accumulated (prefilled with garbage).
  MatchingCostVolume cost(5, 4, 8);
  std::fill(cost.data(), cost.data() + cost.size(), std::uint8_t{7});
  for (int paths : {4, 8}) {
    AggregatedCostVolume sum(5, 4, 8);
    std::fill(sum.data(), sum.data() + sum.size(), std::uint16_t{999});
    cpu_ref::aggregatePaths(cost, 10, 100, paths, sum);
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 5; ++x) {
        for (int d = 0; d < 8; ++d) EXPECT_EQ(sum(x, y, d), paths * 7) << x << "," << y << "," << d;
      }
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
