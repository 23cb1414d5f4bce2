// Census transform (cpu_ref), checked against census strings worked out by hand.
//
// Bit layout (9x7): the 62 comparisons are taken in window raster order (dy = -3..3, dx = -4..4),
// skipping the centre, and shifted in MSB-first. Raster index r = 9*(dy+3) + (dx+4); the centre
// is r = 31, so the comparison number is k = r for r < 31 and k = r - 1 for r > 31, and it lands
// in bit 61 - k of the result. A bit is 1 when the neighbour is strictly less than the centre.
#include <gtest/gtest.h>

#include <bitset>
#include <cstdint>
#include <utility>
#include <vector>

#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

int popcount(std::uint64_t v) { return static_cast<int>(std::bitset<64>(v).count()); }

// Note: the census overloads take ImageView<const uint8_t> / ImageView<const uint16_t>; a mutable
// ImageView<T> is ambiguous between them (its conversion operator deduces the target pixel type),
// so the tests pass const views.

// Bit of the 9x7 census that compares the neighbour at (dx, dy) with the centre (hand formula
// of the header comment, used to name bits; the expected values below are written out as hex).
int census9x7Bit(int dx, int dy) {
  const int r = 9 * (dy + 3) + (dx + 4);
  const int k = r < 31 ? r : r - 1;
  return 61 - k;
}

TEST(CensusTransform, BitPositionsOn9x7Image) {
  // 9x7 image, all 100; the centre pixel (4,3) sees the whole window without clamping.
  Image<std::uint8_t> image(9, 7, 100);
  image(0, 0) = 50;   // dx=-4, dy=-3: r=0,  k=0,  bit 61 (the MSB of the 62 bits) -> 1
  image(8, 6) = 50;   // dx=+4, dy=+3: r=62, k=61, bit 0  (the LSB)              -> 1
  image(5, 3) = 50;   // dx=+1, dy= 0: r=32, k=31, bit 30 (first after centre)   -> 1
  image(4, 2) = 99;   // dx= 0, dy=-1: r=22, k=22, bit 39                        -> 1
  image(3, 3) = 200;  // dx=-1, dy= 0: greater than the centre                   -> 0
  // Every other neighbour equals the centre: not strictly less -> 0.
  Image<std::uint64_t> census(9, 7);
  cpu_ref::censusTransform(std::as_const(image).view(), CensusType::Census9x7, census.view());

  // (1<<61) | (1<<39) | (1<<30) | 1 = 0x2000008040000001
  const std::uint64_t expected = 0x2000008040000001ull;
  EXPECT_EQ(census(4, 3), expected);
  EXPECT_EQ(popcount(census(4, 3)), 4);
  EXPECT_EQ(census9x7Bit(-4, -3), 61);
  EXPECT_EQ(census9x7Bit(4, 3), 0);
  EXPECT_EQ(census9x7Bit(1, 0), 30);
  EXPECT_EQ(census9x7Bit(-1, 0), 31);
  EXPECT_TRUE((census(4, 3) >> 61) & 1u);
  EXPECT_TRUE((census(4, 3) >> 39) & 1u);
  EXPECT_TRUE((census(4, 3) >> 30) & 1u);
  EXPECT_TRUE(census(4, 3) & 1u);
  EXPECT_FALSE((census(4, 3) >> 31) & 1u);  // (3,3) = 200 is not less than 100
  // Only 62 bits are ever used.
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 9; ++x) EXPECT_EQ(census(x, y) >> 62, 0u) << x << "," << y;
  }
}

TEST(CensusTransform, PixelDarkerThanAllNeighboursHas62Bits) {
  // Centre 0, everything else 1: every comparison "neighbour < centre" fails -> 0.
  // Centre 255, everything else 254: all 62 comparisons succeed -> 62 ones = 0x3FFFFFFFFFFFFFFF.
  Image<std::uint8_t> dark(9, 7, 1);
  dark(4, 3) = 0;
  Image<std::uint8_t> bright(9, 7, 254);
  bright(4, 3) = 255;
  Image<std::uint64_t> census(9, 7);
  cpu_ref::censusTransform(std::as_const(dark).view(), CensusType::Census9x7, census.view());
  EXPECT_EQ(census(4, 3), 0u);
  cpu_ref::censusTransform(std::as_const(bright).view(), CensusType::Census9x7, census.view());
  EXPECT_EQ(census(4, 3), 0x3FFFFFFFFFFFFFFFull);
  EXPECT_EQ(popcount(census(4, 3)), 62);
}

TEST(CensusTransform, ConstantImageGivesZero) {
  Image<std::uint8_t> image(11, 9, 77);
  Image<std::uint64_t> census(11, 9, 0xDEADull);
  for (CensusType type : {CensusType::Census9x7, CensusType::CenterSymmetric9x7}) {
    cpu_ref::censusTransform(std::as_const(image).view(), type, census.view());
    for (int y = 0; y < 9; ++y) {
      for (int x = 0; x < 11; ++x) EXPECT_EQ(census(x, y), 0u) << x << "," << y;
    }
  }
}

TEST(CensusTransform, CornerSeesReplicatedBorder) {
  // 2x2 image:   5 3
  //              7 5
  // At (0,0) (centre 5) the clamped window reads x = 0 for dx <= 0, x = 1 for dx >= 1, and
  // y = 0 for dy <= 0, y = 1 for dy >= 1. Only (1,0) = 3 is less than 5, i.e. dy in -3..0 and
  // dx in 1..4: r = 9*(dy+3) + dx+4 -> rows 0..2: k = 5..8, 14..17, 23..26 -> bits 56..53,
  // 47..44, 38..35; row dy=0: r = 32..35 -> k = 31..34 -> bits 30..27. 16 bits:
  // (0xF<<53)|(0xF<<44)|(0xF<<35)|(0xF<<27) = 0x01E0F07878000000.
  // At (1,1) (centre 5): x = 0 for dx <= -1, x = 1 for dx >= 0; y = 0 for dy <= -1. Again only
  // (1,0) = 3 counts: dy in -3..-1, dx in 0..4 -> k = 4..8, 13..17, 22..26 -> bits 57..53,
  // 48..44, 39..35: (0x1F<<53)|(0x1F<<44)|(0x1F<<35) = 0x03E1F0F800000000 (15 bits).
  Image<std::uint8_t> image(2, 2);
  image(0, 0) = 5;
  image(1, 0) = 3;
  image(0, 1) = 7;
  image(1, 1) = 5;
  Image<std::uint64_t> census(2, 2);
  cpu_ref::censusTransform(std::as_const(image).view(), CensusType::Census9x7, census.view());
  EXPECT_EQ(census(0, 0), 0x01E0F07878000000ull);
  EXPECT_EQ(popcount(census(0, 0)), 16);
  EXPECT_EQ(census(1, 1), 0x03E1F0F800000000ull);
  EXPECT_EQ(popcount(census(1, 1)), 15);
  // (1,0) = 3 is the smallest pixel: nothing is less than it.
  EXPECT_EQ(census(1, 0), 0u);
  // (0,1) = 7 is the largest: 3 and 5 are less, 7 itself (replicated) is not. Pixels with value
  // 7 are those with x = 0 and y = 1 i.e. dx <= 0 and dy >= 0: 4 rows x 5 cols = 20 minus the
  // centre = 19 zeros, so 62 - 19 = 43 ones.
  EXPECT_EQ(popcount(census(0, 1)), 43);
}

TEST(CensusTransform, CenterSymmetricBitsByHand) {
  // Centre-symmetric 9x7: 31 pairs (a, mirror b) for dy = -3..-1 with dx = -4..4 (27 pairs) and
  // dy = 0 with dx = -4..-1 (4 pairs); pair number k = 9*(dy+3) + dx+4, MSB-first -> bit 30 - k.
  // The bit is a < b with a = I(x+dx, y+dy), b = I(x-dx, y-dy).
  Image<std::uint8_t> image(9, 7, 100);
  image(0, 0) = 50;   // pair dx=-4,dy=-3 (k=0, bit 30): a=50  < b=I(8,6)=100 -> 1
  image(7, 5) = 150;  // mirror of dx=-3,dy=-2 (k=10, bit 20): a=I(1,1)=100 < b=150 -> 1
  image(3, 3) = 50;   // pair dx=-1,dy=0 (k=30, bit 0): a=50 < b=I(5,3)=100 -> 1
  image(4, 0) = 200;  // pair dx=0,dy=-3 (k=4, bit 26): a=200 < b=I(4,6)=100? no -> 0
  Image<std::uint64_t> census(9, 7);
  cpu_ref::censusTransform(std::as_const(image).view(), CensusType::CenterSymmetric9x7, census.view());
  // (1<<30) | (1<<20) | 1 = 0x40100001
  EXPECT_EQ(census(4, 3), 0x40100001ull);
  EXPECT_EQ(popcount(census(4, 3)), 3);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 9; ++x) EXPECT_EQ(census(x, y) >> 31, 0u) << x << "," << y;
  }
}

TEST(CensusTransform, CenterSymmetricAllPairsSet) {
  // Vertical ramp I(x, y) = 10*y: a = I(., y+dy) < b = I(., y-dy) for every dy < 0, and for dy = 0
  // a == b -> 0. So at an interior pixel the 27 pairs with dy < 0 are 1 and the 4 with dy = 0
  // are 0: bits 30..4 set = 0x7FFFFFF0.
  Image<std::uint8_t> image(9, 7);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 9; ++x) image(x, y) = static_cast<std::uint8_t>(10 * y);
  }
  Image<std::uint64_t> census(9, 7);
  cpu_ref::censusTransform(std::as_const(image).view(), CensusType::CenterSymmetric9x7, census.view());
  EXPECT_EQ(census(4, 3), 0x7FFFFFF0ull);
  EXPECT_EQ(popcount(census(4, 3)), 27);
}

Image<std::uint8_t> textured8(int width, int height) {
  Image<std::uint8_t> image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image(x, y) = static_cast<std::uint8_t>((x * 37 + y * 91 + x * y * 13 + (x ^ y) * 7) % 256);
    }
  }
  return image;
}

TEST(CensusTransform, SixteenBitEqualsEightBitTimes257) {
  const int width = 13;
  const int height = 10;
  const Image<std::uint8_t> image8 = textured8(width, height);
  Image<std::uint16_t> image16(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image16(x, y) = static_cast<std::uint16_t>(image8(x, y) * 257);
  }
  for (CensusType type : {CensusType::Census9x7, CensusType::CenterSymmetric9x7}) {
    Image<std::uint64_t> census8(width, height);
    Image<std::uint64_t> census16(width, height, ~0ull);
    cpu_ref::censusTransform(std::as_const(image8).view(), type, census8.view());
    cpu_ref::censusTransform(std::as_const(image16).view(), type, census16.view());
    int nonZero = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        EXPECT_EQ(census8(x, y), census16(x, y)) << x << "," << y;
        if (census8(x, y) != 0) ++nonZero;
      }
    }
    EXPECT_GT(nonZero, width * height / 2);  // the texture really exercises the comparisons
  }
}

TEST(CensusTransform, PaddedStrideEqualsDenseCopy) {
  const int width = 11;
  const int height = 9;
  const std::ptrdiff_t stride = 16;
  const Image<std::uint8_t> dense = textured8(width, height);
  // Padding columns hold extreme values: reading them by mistake changes the census.
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(stride) * height, 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < stride; ++x) {
      padded[static_cast<std::size_t>(y * stride + x)] =
          x < width ? dense(x, y) : static_cast<std::uint8_t>(x % 2 == 0 ? 0 : 255);
    }
  }
  const ImageView<const std::uint8_t> paddedView(padded.data(), width, height, stride);
  const std::uint64_t sentinel = 0x0123456789ABCDEFull;
  for (CensusType type : {CensusType::Census9x7, CensusType::CenterSymmetric9x7}) {
    Image<std::uint64_t> expected(width, height);
    cpu_ref::censusTransform(std::as_const(dense).view(), type, expected.view());
    std::vector<std::uint64_t> out(static_cast<std::size_t>(stride) * height, sentinel);
    cpu_ref::censusTransform(paddedView, type,
                             ImageView<std::uint64_t>(out.data(), width, height, stride));
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < stride; ++x) {
        const std::uint64_t got = out[static_cast<std::size_t>(y * stride + x)];
        if (x < width) {
          EXPECT_EQ(got, expected(x, y)) << x << "," << y;
        } else {
          EXPECT_EQ(got, sentinel) << "padding written at " << x << "," << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
