#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>

#include "eval/baselines.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 100;
constexpr int kShift = 8;  // true disparity of the synthetic pair [px]

/// Random texture (SGBM needs texture everywhere), seen by a right camera kShift px further:
/// right(x - kShift) = left(x), i.e. every left pixel has disparity kShift.
struct Pair {
  cv::Mat left, right;
};
Pair texturedPair() {
  cv::RNG rng(7);
  cv::Mat wide(kHeight, kWidth + kShift, CV_8UC1);
  rng.fill(wide, cv::RNG::UNIFORM, 0, 256);
  return {wide(cv::Rect(0, 0, kWidth, kHeight)).clone(), wide(cv::Rect(kShift, 0, kWidth, kHeight)).clone()};
}

TEST(OpencvSgbm, FindsTheShiftOfATexturedPair) {
  const Pair pair = texturedPair();
  const Image<std::int16_t> d = opencvSgbm(pair.left, pair.right, 32, 5);
  ASSERT_EQ(d.width(), kWidth);
  ASSERT_EQ(d.height(), kHeight);
  int scored = 0, right = 0;
  for (int y = 5; y < kHeight - 5; ++y) {
    for (int x = 40; x < kWidth - 5; ++x) {  // away from the left border SGBM cannot match
      const std::int16_t v = d(x, y);
      ASSERT_TRUE(v == kInvalidDisparity || v >= 0) << "at " << x << "," << y;
      ++scored;
      if (v != kInvalidDisparity && std::abs(v - kShift * kDisparityScale) <= kDisparityScale) ++right;
    }
  }
  EXPECT_GT(right, 0.9 * scored);
}

TEST(OpencvSgbm, SixteenBitInputUsesTheHighByte) {
  const Pair pair = texturedPair();
  cv::Mat left16, right16, noise(kHeight, kWidth, CV_16UC1);
  pair.left.convertTo(left16, CV_16U, 256.0);
  pair.right.convertTo(right16, CV_16U, 256.0);
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 256);  // low bytes must not matter
  left16 += noise;
  right16 += noise;
  const Image<std::int16_t> eight = opencvSgbm(pair.left, pair.right, 32, 5);
  const Image<std::int16_t> sixteen = opencvSgbm(left16, right16, 32, 5);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(eight(x, y), sixteen(x, y)) << "at " << x << "," << y;
  }
}

TEST(OpencvSgbm, RejectsBadInput) {
  const Pair pair = texturedPair();
  const cv::Mat smaller = pair.right(cv::Rect(0, 0, kWidth - 1, kHeight)).clone();
  EXPECT_THROW(opencvSgbm(pair.left, smaller), std::invalid_argument);
  EXPECT_THROW(opencvSgbm(pair.left, pair.right, 30), std::invalid_argument);
  EXPECT_THROW(opencvSgbm(pair.left, pair.right, 32, 4), std::invalid_argument);
  cv::Mat color;
  cv::merge(std::vector<cv::Mat>{pair.left, pair.left, pair.left}, color);
  EXPECT_THROW(opencvSgbm(color, color), std::invalid_argument);
}

constexpr double kFocalBaseline = 400.0;  // f*b [px*m]

/// LiDAR-like sparse points: every 4th row from `firstRow` down, every 3rd column.
Image<std::int16_t> sparsePlane(std::int16_t disparity16, int firstRow) {
  Image<std::int16_t> sparse(kWidth, kHeight, kInvalidDisparity);
  for (int y = firstRow; y < kHeight; y += 4) {
    for (int x = 0; x < kWidth; x += 3) sparse(x, y) = disparity16;
  }
  return sparse;
}

TEST(MorphologicalCompletion, FillsAPlaneCompletelyAndExactly) {
  // d = 20 px -> z = 20 m; every step keeps a constant depth, so the result is exact.
  const std::int16_t d16 = 20 * kDisparityScale;
  const Image<std::int16_t> dense = morphologicalCompletion(sparsePlane(d16, 50), kFocalBaseline);
  ASSERT_EQ(dense.width(), kWidth);
  ASSERT_EQ(dense.height(), kHeight);
  for (int y = 0; y < kHeight; ++y) {  // rows above the first point too: extension to the top
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(dense(x, y), d16) << "at " << x << "," << y;
  }
}

TEST(MorphologicalCompletion, KeepsTwoDepthsApartAwayFromTheirEdge) {
  Image<std::int16_t> sparse(kWidth, kHeight, kInvalidDisparity);
  for (int y = 0; y < kHeight; y += 4) {
    for (int x = 0; x < kWidth; x += 3) {
      sparse(x, y) = x < kWidth / 2 ? 40 * kDisparityScale   // near: z = 10 m
                                    : 10 * kDisparityScale;  // far: z = 40 m
    }
  }
  const Image<std::int16_t> dense = morphologicalCompletion(sparse, kFocalBaseline);
  for (int y = 10; y < kHeight - 10; ++y) {
    EXPECT_EQ(dense(20, y), 40 * kDisparityScale);
    EXPECT_EQ(dense(kWidth - 20, y), 10 * kDisparityScale);
  }
}

TEST(MorphologicalCompletion, NoPointsGiveNoValues) {
  const Image<std::int16_t> empty(kWidth, kHeight, kInvalidDisparity);
  const Image<std::int16_t> dense = morphologicalCompletion(empty, kFocalBaseline);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(dense(x, y), kInvalidDisparity);
  }
}

TEST(MorphologicalCompletion, RejectsANonPositiveFocalBaseline) {
  EXPECT_THROW(morphologicalCompletion(sparsePlane(320, 0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
