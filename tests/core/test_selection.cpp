// Disparity selection, left-right check and median filter (cpu_ref), checked by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

// One pixel per cost row: a width x 1 volume whose pixel x holds rows[x].
AggregatedCostVolume rowVolume(const std::vector<std::vector<int>>& rows) {
  const int D = static_cast<int>(rows.front().size());
  AggregatedCostVolume sum(static_cast<int>(rows.size()), 1, D);
  for (int x = 0; x < static_cast<int>(rows.size()); ++x) {
    for (int d = 0; d < D; ++d) {
      sum(x, 0, d) = static_cast<std::uint16_t>(rows[static_cast<std::size_t>(x)][static_cast<std::size_t>(d)]);
    }
  }
  return sum;
}

struct Selected {
  Image<std::int16_t> disparity16;
  Image<std::int16_t> bestIndex;
  Selected(int width, int height) : disparity16(width, height, 1234), bestIndex(width, height, 99) {}
  SelectedDisparity view() { return SelectedDisparity{disparity16.view(), bestIndex.view()}; }
};

Selected selectAll(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio, bool subpixel) {
  Selected out(sum.width(), sum.height());
  cpu_ref::selectDisparity(sum, minDisparity, uniquenessRatio, subpixel, out.view());
  return out;
}

// ---------------------------------------------------------------------------------------------
// selectDisparity
// ---------------------------------------------------------------------------------------------

TEST(SelectDisparity, WinnerTakesAllFirstMinimumWinsTies) {
  // pixel 0: {9, 3, 7, 3, 8}: minimum 3 at d = 1 and d = 3 -> first, d = 1 -> 16.
  // pixel 1: {5, 5, 5, 5, 5}: all tie -> d = 0 -> 0.
  // pixel 2: {9, 8, 7, 6, 5}: d = 4 -> 64.
  const AggregatedCostVolume sum = rowVolume({{9, 3, 7, 3, 8}, {5, 5, 5, 5, 5}, {9, 8, 7, 6, 5}});
  Selected out = selectAll(sum, 0, 0, false);
  EXPECT_EQ(out.bestIndex(0, 0), 1);
  EXPECT_EQ(out.disparity16(0, 0), 16);
  EXPECT_EQ(out.bestIndex(1, 0), 0);
  EXPECT_EQ(out.disparity16(1, 0), 0);
  EXPECT_EQ(out.bestIndex(2, 0), 4);
  EXPECT_EQ(out.disparity16(2, 0), 64);
}

TEST(SelectDisparity, ParabolaSubpixelByHand) {
  // {20, 10, 4, 8, 30}: best d = 2 with S- = 10, S = 4, S+ = 8.
  // offset = (S- - S+) / (2 (S- + S+ - 2S)) = 2 / (2 * 10) = 0.1 px = 1.6 /16 -> 2.
  // disparity16 = 2*16 + 2 = 34.
  // {30, 8, 4, 10, 20}: mirrored, -0.1 px = -1.6/16 -> -2 -> 30.
  const AggregatedCostVolume sum = rowVolume({{20, 10, 4, 8, 30}, {30, 8, 4, 10, 20}});
  Selected out = selectAll(sum, 0, 0, true);
  EXPECT_EQ(out.disparity16(0, 0), 34);
  EXPECT_EQ(out.bestIndex(0, 0), 2);
  EXPECT_EQ(out.disparity16(1, 0), 30);
  EXPECT_EQ(out.bestIndex(1, 0), 2);
}

TEST(SelectDisparity, SubpixelRoundsHalfAwayFromZero) {
  // {50, 19, 4, 21, 50}: S- = 19, S = 4, S+ = 21, curvature 19 + 21 - 8 = 32.
  // offset16 = (19 - 21) * 16 / (2 * 32) = -32 / 64 = -0.5 -> -1 (away from zero; rounding half
  // up or truncating would give 0). disparity16 = 32 - 1 = 31.
  // Mirrored {50, 21, 4, 19, 50}: +0.5 -> +1 -> 33.
  const AggregatedCostVolume sum = rowVolume({{50, 19, 4, 21, 50}, {50, 21, 4, 19, 50}});
  Selected out = selectAll(sum, 0, 0, true);
  EXPECT_EQ(out.disparity16(0, 0), 31);
  EXPECT_EQ(out.disparity16(1, 0), 33);
}

TEST(SelectDisparity, NoSubpixelAtRangeEndsOrWhenOff) {
  // best at d = 0 ({3, 5, 9, 9, 9}) -> exactly 0; best at d = D-1 ({9, 9, 9, 5, 3}) -> exactly 64,
  // even though a one-sided fit would move them.
  const AggregatedCostVolume ends = rowVolume({{3, 5, 9, 9, 9}, {9, 9, 9, 5, 3}});
  Selected out = selectAll(ends, 0, 0, true);
  EXPECT_EQ(out.disparity16(0, 0), 0);
  EXPECT_EQ(out.disparity16(1, 0), 64);
  // subpixel = false on the 10, 4, 8 example: 32, not 34.
  const AggregatedCostVolume inner = rowVolume({{20, 10, 4, 8, 30}});
  Selected off = selectAll(inner, 0, 0, false);
  EXPECT_EQ(off.disparity16(0, 0), 32);
}

TEST(SelectDisparity, MinDisparityOffsetsTheOutput) {
  // {20, 10, 4, 8, 30}: best index 2, offset +2/16.
  // minDisparity -3: (-3 + 2)*16 + 2 = -14;  minDisparity 5: (5 + 2)*16 + 2 = 114.
  // bestIndex stays the index d - minDisparity = 2.
  const AggregatedCostVolume sum = rowVolume({{20, 10, 4, 8, 30}});
  Selected negative = selectAll(sum, -3, 0, true);
  EXPECT_EQ(negative.disparity16(0, 0), -14);
  EXPECT_EQ(negative.bestIndex(0, 0), 2);
  Selected positive = selectAll(sum, 5, 0, true);
  EXPECT_EQ(positive.disparity16(0, 0), 114);
  EXPECT_EQ(positive.bestIndex(0, 0), 2);
}

TEST(SelectDisparity, UniquenessRatio) {
  // Rule: invalid if some d with |d - best| > 1 has S[d]*(100-u) < S[best]*100.
  // u = 10, S[best] = 40 at d = 2 -> threshold 4000:
  //   pixel 0 {100, 50, 40, 45, 60}: far d=0 9000, d=4 5400 >= 4000 -> unique -> 32.
  //   pixel 1 {43, 50, 40, 45, 60}: d=0 43*90 = 3870 < 4000 -> invalid.
  //   pixel 2 {100, 40, 40, 41, 100}: best d=1 (first of the tie); d=2 is a neighbour (ignored),
  //           but d=3 is 2 away: 41*90 = 3690 < 4000 -> invalid.
  //   pixel 3 {100, 90, 40, 40, 100}: best d=2; the tie at d=3 is a neighbour (ignored);
  //           d=0, d=4: 9000 -> unique -> 32.
  const AggregatedCostVolume sum = rowVolume(
      {{100, 50, 40, 45, 60}, {43, 50, 40, 45, 60}, {100, 40, 40, 41, 100}, {100, 90, 40, 40, 100}});
  Selected out = selectAll(sum, 0, 10, false);
  EXPECT_EQ(out.disparity16(0, 0), 32);
  EXPECT_EQ(out.bestIndex(0, 0), 2);
  EXPECT_EQ(out.disparity16(1, 0), kInvalidDisparity);
  EXPECT_EQ(out.bestIndex(1, 0), -1);
  EXPECT_EQ(out.disparity16(2, 0), kInvalidDisparity);
  EXPECT_EQ(out.bestIndex(2, 0), -1);
  EXPECT_EQ(out.disparity16(3, 0), 32);
  EXPECT_EQ(out.bestIndex(3, 0), 2);
  // uniquenessRatio 0 switches the check off: pixel 1 -> d = 2.
  Selected off = selectAll(sum, 0, 0, false);
  EXPECT_EQ(off.disparity16(1, 0), 32);
  EXPECT_EQ(off.bestIndex(1, 0), 2);
}

TEST(SelectDisparity, UniquenessBoundaryIsStrict) {
  // u = 20, S[best] = 40 -> threshold 4000. S[d] = 50: 50*80 = 4000, not < 4000 -> kept.
  // S[d] = 49: 49*80 = 3920 < 4000 -> rejected. A far tie (40*80 = 3200) -> rejected.
  const AggregatedCostVolume sum =
      rowVolume({{50, 70, 40, 70, 90}, {49, 70, 40, 70, 90}, {40, 70, 40, 70, 90}});
  Selected out = selectAll(sum, 0, 20, false);
  EXPECT_EQ(out.disparity16(0, 0), 32);
  EXPECT_EQ(out.disparity16(1, 0), kInvalidDisparity);
  EXPECT_EQ(out.bestIndex(1, 0), -1);
  EXPECT_EQ(out.disparity16(2, 0), kInvalidDisparity);  // best d = 0, S[2] = 40 is 2 away
}

// ---------------------------------------------------------------------------------------------
// rightDisparityIndex: argmin_d sum(xr + minDisparity + d, d) over d with that x in the image
// ---------------------------------------------------------------------------------------------

// width 4, D = 3:  sum(0) = {5,9,9}  sum(1) = {8,2,7}  sum(2) = {6,4,1}  sum(3) = {3,7,6}
AggregatedCostVolume rightTestVolume() {
  return rowVolume({{5, 9, 9}, {8, 2, 7}, {6, 4, 1}, {3, 7, 6}});
}

std::vector<int> rightIndices(const AggregatedCostVolume& sum, int minDisparity) {
  Image<std::int16_t> index(sum.width(), sum.height(), 77);
  cpu_ref::rightDisparityIndex(sum, minDisparity, index.view());
  std::vector<int> result;
  for (int x = 0; x < sum.width(); ++x) result.push_back(index(x, 0));
  return result;
}

TEST(RightDisparityIndex, ByHand) {
  const AggregatedCostVolume sum = rightTestVolume();
  // minDisparity 0, x = xr + d:
  //   xr=0: (0,d0)=5 (1,d1)=2 (2,d2)=1 -> 2
  //   xr=1: (1,d0)=8 (2,d1)=4 (3,d2)=6 -> 1
  //   xr=2: (2,d0)=6 (3,d1)=7 (x=4 out) -> 0
  //   xr=3: (3,d0)=3 -> 0
  EXPECT_EQ(rightIndices(sum, 0), (std::vector<int>{2, 1, 0, 0}));
  // minDisparity 1, x = xr + 1 + d:
  //   xr=0: (1,d0)=8 (2,d1)=4 (3,d2)=6 -> 1;  xr=1: (2,d0)=6 (3,d1)=7 -> 0;
  //   xr=2: (3,d0)=3 -> 0;  xr=3: x >= 4 for every d -> -1
  EXPECT_EQ(rightIndices(sum, 1), (std::vector<int>{1, 0, 0, -1}));
  // minDisparity -1, x = xr - 1 + d:
  //   xr=0: (x=-1 out) (0,d1)=9 (1,d2)=7 -> 2;  xr=1: (0,d0)=5 (1,d1)=2 (2,d2)=1 -> 2;
  //   xr=2: (1,d0)=8 (2,d1)=4 (3,d2)=6 -> 1;    xr=3: (2,d0)=6 (3,d1)=7 (x=4 out) -> 0
  EXPECT_EQ(rightIndices(sum, -1), (std::vector<int>{2, 2, 1, 0}));
}

TEST(RightDisparityIndex, TiesTakeTheFirstValidIndex) {
  // All costs equal: the first d whose left pixel lies inside wins.
  // minDisparity 0: d = 0 is always inside -> 0. minDisparity -1: xr = 0 needs d >= 1 -> 1.
  const AggregatedCostVolume sum = rowVolume({{5, 5}, {5, 5}, {5, 5}});
  EXPECT_EQ(rightIndices(sum, 0), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(rightIndices(sum, -1), (std::vector<int>{1, 0, 0}));
}

// ---------------------------------------------------------------------------------------------
// leftRightCheck
// ---------------------------------------------------------------------------------------------

// width 7, minDisparity 0; rightIndex = {0, 1, 3, -1, 0, 0, 0}
//   x  best  disparity16  xr = x - best  rightIndex(xr)  |diff|
//   0   0        3           0              0             0
//   1   2       32          -1             (none)         -
//   2   1       17           1              1             0
//   3   1       15           2              3             2
//   4   2       33           2              3             1
//   5  -1      INV           -              -             -   (already invalid)
//   6   3       48           3             -1             -   (right has no winner)
struct LrCase {
  Selected selected{7, 1};
  Image<std::int16_t> rightIndex{7, 1};
  LrCase() {
    const int best[7] = {0, 2, 1, 1, 2, -1, 3};
    const int disp[7] = {3, 32, 17, 15, 33, kInvalidDisparity, 48};
    const int right[7] = {0, 1, 3, -1, 0, 0, 0};
    for (int x = 0; x < 7; ++x) {
      selected.bestIndex(x, 0) = static_cast<std::int16_t>(best[x]);
      selected.disparity16(x, 0) = static_cast<std::int16_t>(disp[x]);
      rightIndex(x, 0) = static_cast<std::int16_t>(right[x]);
    }
  }
  void run(ImageView<const std::uint8_t> support, int minDisparity, int maxDiff, bool keepNoCounterpart) {
    cpu_ref::leftRightCheck(selected.view(), rightIndex.view(), support, minDisparity, maxDiff,
                            keepNoCounterpart);
  }
  void expectValid(int x, int disparity16, int best) const {
    EXPECT_EQ(selected.disparity16(x, 0), disparity16) << "x " << x;
    EXPECT_EQ(selected.bestIndex(x, 0), best) << "x " << x;
  }
  void expectInvalid(int x) const {
    EXPECT_EQ(selected.disparity16(x, 0), kInvalidDisparity) << "x " << x;
    EXPECT_EQ(selected.bestIndex(x, 0), -1) << "x " << x;
  }
};

TEST(LeftRightCheck, ConsistentKeptInconsistentRemoved) {
  LrCase c;
  c.run(ImageView<const std::uint8_t>(), 0, 1, true);
  c.expectValid(0, 3, 0);    // diff 0
  c.expectValid(1, 32, 2);   // no counterpart, kept
  c.expectValid(2, 17, 1);   // diff 0
  c.expectInvalid(3);        // diff 2 > 1
  c.expectValid(4, 33, 2);   // diff 1 <= 1
  c.expectInvalid(5);        // stays invalid
  c.expectInvalid(6);        // right index -1
}

TEST(LeftRightCheck, RightPixelWithoutWinnerRemoved) {
  // x = 1, best 0 -> xr = 1, rightIndex(1) = -1: no right winner. |-1 - 0| = 1 would pass a
  // tolerance of 1 if -1 were compared as an index; it must be removed.
  Selected selected(3, 1);
  Image<std::int16_t> rightIndex(3, 1, -1);
  for (int x = 0; x < 3; ++x) {
    selected.bestIndex(x, 0) = 0;
    selected.disparity16(x, 0) = 5;
  }
  cpu_ref::leftRightCheck(selected.view(), rightIndex.view(), ImageView<const std::uint8_t>(), 0, 1, true);
  for (int x = 0; x < 3; ++x) {
    EXPECT_EQ(selected.disparity16(x, 0), kInvalidDisparity) << x;
    EXPECT_EQ(selected.bestIndex(x, 0), -1) << x;
  }
}

TEST(LeftRightCheck, Disp12MaxDiffTolerance) {
  LrCase strict;
  strict.run(ImageView<const std::uint8_t>(), 0, 0, true);
  strict.expectValid(0, 3, 0);
  strict.expectValid(2, 17, 1);
  strict.expectInvalid(3);  // diff 2
  strict.expectInvalid(4);  // diff 1 > 0
  LrCase loose;
  loose.run(ImageView<const std::uint8_t>(), 0, 2, true);
  loose.expectValid(3, 15, 1);  // diff 2 <= 2
  loose.expectValid(4, 33, 2);
  loose.expectInvalid(6);       // -1 never matches
}

TEST(LeftRightCheck, SupportedPixelKept) {
  // support 1 at x = 3 (diff 2) and x = 6 (right index -1): both kept; x = 4 (no support,
  // tolerance 0) removed.
  LrCase c;
  Image<std::uint8_t> support(7, 1, 0);
  support(3, 0) = 1;
  support(6, 0) = 1;
  c.run(support.view(), 0, 0, true);
  c.expectValid(3, 15, 1);
  c.expectValid(6, 48, 3);
  c.expectInvalid(4);
  c.expectValid(0, 3, 0);
}

TEST(LeftRightCheck, NoCounterpartRemovedWhenNotKept) {
  LrCase c;
  c.run(ImageView<const std::uint8_t>(), 0, 1, false);
  c.expectInvalid(1);       // x - d = -1
  c.expectValid(0, 3, 0);   // the others as with keepNoCounterpart = true
  c.expectValid(2, 17, 1);
  c.expectValid(4, 33, 2);
  c.expectInvalid(3);
}

TEST(LeftRightCheck, MinDisparityShiftsTheRightPixel) {
  // minDisparity 2: xr = x - (2 + best).
  //   x=4, best 1 -> xr = 1: rightIndex(1) = 1 -> diff 0 -> kept
  //   x=2, best 1 -> xr = -1: no counterpart (removed with keepNoCounterpart = false)
  //   x=6, best 0 -> xr = 4: rightIndex(4) = 0 -> kept
  //   x=5, best 1 -> xr = 2: rightIndex(2) = 3 -> diff 2 -> removed
  // minDisparity -3, x=5, best 0: xr = 8 >= width -> no counterpart.
  Selected selected(7, 1);
  Image<std::int16_t> rightIndex(7, 1);
  const int right[7] = {0, 1, 3, -1, 0, 0, 0};
  for (int x = 0; x < 7; ++x) {
    rightIndex(x, 0) = static_cast<std::int16_t>(right[x]);
    selected.bestIndex(x, 0) = -1;
    selected.disparity16(x, 0) = kInvalidDisparity;
  }
  auto setPixel = [&](int x, int best, int disparity16) {
    selected.bestIndex(x, 0) = static_cast<std::int16_t>(best);
    selected.disparity16(x, 0) = static_cast<std::int16_t>(disparity16);
  };
  setPixel(4, 1, 48);
  setPixel(2, 1, 48);
  setPixel(6, 0, 32);
  setPixel(5, 1, 48);
  cpu_ref::leftRightCheck(selected.view(), rightIndex.view(), ImageView<const std::uint8_t>(), 2, 1, false);
  EXPECT_EQ(selected.disparity16(4, 0), 48);
  EXPECT_EQ(selected.bestIndex(4, 0), 1);
  EXPECT_EQ(selected.disparity16(2, 0), kInvalidDisparity);
  EXPECT_EQ(selected.disparity16(6, 0), 32);
  EXPECT_EQ(selected.disparity16(5, 0), kInvalidDisparity);
  EXPECT_EQ(selected.bestIndex(5, 0), -1);

  Selected negative(7, 1);
  for (int x = 0; x < 7; ++x) {
    negative.bestIndex(x, 0) = -1;
    negative.disparity16(x, 0) = kInvalidDisparity;
  }
  negative.bestIndex(5, 0) = 0;
  negative.disparity16(5, 0) = -48;
  cpu_ref::leftRightCheck(negative.view(), rightIndex.view(), ImageView<const std::uint8_t>(), -3, 1, true);
  EXPECT_EQ(negative.disparity16(5, 0), -48);
  cpu_ref::leftRightCheck(negative.view(), rightIndex.view(), ImageView<const std::uint8_t>(), -3, 1, false);
  EXPECT_EQ(negative.disparity16(5, 0), kInvalidDisparity);
}

// ---------------------------------------------------------------------------------------------
// medianFilter: median of the valid pixels of a window cropped at the border, lower median for
// even counts; invalid pixels stay invalid.
// ---------------------------------------------------------------------------------------------

Image<std::int16_t> imageFrom(const std::vector<std::vector<int>>& rows) {
  Image<std::int16_t> image(static_cast<int>(rows.front().size()), static_cast<int>(rows.size()));
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      image(x, y) = static_cast<std::int16_t>(rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]);
    }
  }
  return image;
}

void expectImage(const Image<std::int16_t>& image, const std::vector<std::vector<int>>& expected) {
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      EXPECT_EQ(image(x, y), expected[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]) << x << "," << y;
    }
  }
}

TEST(MedianFilter, ThreeByThreeByHand) {
  // 1 9 2 8
  // 7 3 6 4
  // 5 5 0 10
  // (0,0): {1,9,7,3} -> 1 3 7 9 -> lower median 3    (1,0): {1,9,2,7,3,6} -> 1 2 3 6 7 9 -> 3
  // (2,0): {9,2,8,3,6,4} -> 2 3 4 6 8 9 -> 4         (3,0): {2,8,6,4} -> 2 4 6 8 -> 4
  // (0,1): {1,9,7,3,5,5} -> 1 3 5 5 7 9 -> 5         (1,1): 0 1 2 3 5 5 6 7 9 -> 5
  // (2,1): 0 2 3 4 5 6 8 9 10 -> 5                   (3,1): {2,8,6,4,0,10} -> 0 2 4 6 8 10 -> 4
  // (0,2): {7,3,5,5} -> 3 5 5 7 -> 5                 (1,2): {7,3,6,5,5,0} -> 0 3 5 5 6 7 -> 5
  // (2,2): {3,6,4,5,0,10} -> 0 3 4 5 6 10 -> 4       (3,2): {6,4,0,10} -> 0 4 6 10 -> 4
  const Image<std::int16_t> in = imageFrom({{1, 9, 2, 8}, {7, 3, 6, 4}, {5, 5, 0, 10}});
  Image<std::int16_t> out(4, 3, -1);
  cpu_ref::medianFilter(in.view(), 3, out.view());
  expectImage(out, {{3, 3, 4, 4}, {5, 5, 5, 4}, {5, 5, 4, 4}});
}

TEST(MedianFilter, FiveByFiveByHand) {
  // A permutation of 1..25.
  const Image<std::int16_t> in = imageFrom({{12, 3, 25, 7, 18},
                                            {9, 21, 1, 14, 6},
                                            {17, 4, 11, 23, 2},
                                            {8, 20, 15, 5, 24},
                                            {13, 10, 22, 16, 19}});
  Image<std::int16_t> out(5, 5, -1);
  cpu_ref::medianFilter(in.view(), 5, out.view());
  // (2,2): all 25 values 1..25 -> 13.
  EXPECT_EQ(out(2, 2), 13);
  // (0,0): x,y in 0..2: 1 3 4 9 11 12 17 21 25 -> 11.
  EXPECT_EQ(out(0, 0), 11);
  // (2,0): rows 0..2, 15 values: 1 2 3 4 6 7 9 [11] 12 14 17 18 21 23 25 -> 11.
  EXPECT_EQ(out(2, 0), 11);
  // (1,1): x,y in 0..3, 16 values: 1 3 4 5 7 8 9 [11] 12 14 15 17 20 21 23 25 -> lower median 11
  // (the upper one would be 12).
  EXPECT_EQ(out(1, 1), 11);
  // (4,4): x,y in 2..4: 2 5 11 15 [16] 19 22 23 24 -> 16.
  EXPECT_EQ(out(4, 4), 16);
  // (0,4): x 0..2, y 2..4: 4 8 10 11 [13] 15 17 20 22 -> 13.
  EXPECT_EQ(out(0, 4), 13);
  // (0,2): x 0..2, all rows, 15 values: 1 3 4 8 9 10 11 [12] 13 15 17 20 21 22 25 -> 12.
  EXPECT_EQ(out(0, 2), 12);
  // (4,2): x 2..4, all rows: 1 2 5 6 7 11 14 [15] 16 18 19 22 23 24 25 -> 15.
  EXPECT_EQ(out(4, 2), 15);
  // (3,0): x 1..4, y 0..2, 12 values: 1 2 3 4 6 [7] 11 14 18 21 23 25 -> lower median 7 (upper 11).
  EXPECT_EQ(out(3, 0), 7);
}

TEST(MedianFilter, InvalidPixelsIgnored) {
  constexpr int I = kInvalidDisparity;
  // 5 I 9
  // 1 4 I
  // I 8 2
  // (1,1): valid {5,9,1,4,8,2} -> 1 2 4 5 8 9 -> lower median 4 (counting the three invalid
  //        values -32768 would give 2).
  // (0,0): {5,1,4} -> 1 4 5 -> 4.   (2,0): {9,4} -> lower 4.   (0,1): {5,1,4,8} -> 1 4 5 8 -> 4.
  // (1,2): {1,4,8,2} -> 1 2 4 8 -> 2.   (2,2): {4,8,2} -> 4.
  // (1,0), (2,1), (0,2) are invalid and stay invalid.
  const Image<std::int16_t> in = imageFrom({{5, I, 9}, {1, 4, I}, {I, 8, 2}});
  Image<std::int16_t> out(3, 3, -1);
  cpu_ref::medianFilter(in.view(), 3, out.view());
  expectImage(out, {{4, I, 4}, {4, 4, I}, {I, 2, 4}});
}

TEST(MedianFilter, SizeZeroAndOneCopy) {
  constexpr int I = kInvalidDisparity;
  const std::vector<std::vector<int>> values = {{1, 9, 2, 8}, {7, I, 6, 4}, {5, 5, 0, -10}};
  const Image<std::int16_t> in = imageFrom(values);
  for (int size : {0, 1}) {
    Image<std::int16_t> out(4, 3, 77);
    cpu_ref::medianFilter(in.view(), size, out.view());
    expectImage(out, values);
  }
}

}  // namespace
}  // namespace lidar_sgm
