#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "eval/frame_pictures.hpp"
#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "eval/pictures.hpp"
#include "eval/plots.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

// ---------------------------------------------------------------------------------------------
// niceTicks

/// True when `step` is 1, 2 or 5 times a power of ten.
bool isNiceStep(double step) {
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  for (double nice : {1.0, 2.0, 5.0}) {
    if (std::abs(mantissa - nice) < 1e-6) return true;
  }
  return false;
}

TEST(NiceTicks, UnitRangeInFifths) {
  const std::vector<double> ticks = niceTicks(0.0, 1.0);
  const std::vector<double> expected = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  ASSERT_EQ(ticks.size(), expected.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-12);
}

TEST(NiceTicks, OddRangeGetsTicksInsideWithANiceStep) {
  const std::vector<double> ticks = niceTicks(0.31, 0.97);
  ASSERT_GE(ticks.size(), 3u);
  EXPECT_LE(ticks.size(), 8u);
  const double step = ticks[1] - ticks[0];
  EXPECT_TRUE(isNiceStep(step)) << step;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_GE(ticks[i], 0.31);
    EXPECT_LE(ticks[i], 0.97);
    if (i > 0) {
      EXPECT_NEAR(ticks[i] - ticks[i - 1], step, 1e-12);
    }
    EXPECT_NEAR(std::remainder(ticks[i], step), 0.0, 1e-9);  // multiples of the step
  }
}

TEST(NiceTicks, LargeAndDegenerateRanges) {
  const std::vector<double> ticks = niceTicks(0.0, 730.0);
  ASSERT_FALSE(ticks.empty());
  EXPECT_TRUE(isNiceStep(ticks[1] - ticks[0]));
  EXPECT_EQ(niceTicks(1.0, 0.0), niceTicks(0.0, 1.0));
  EXPECT_FALSE(niceTicks(5.0, 5.0).empty());
  EXPECT_THROW(niceTicks(0.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// linePlot

int countColor(const cv::Mat& image, const cv::Scalar& color) {
  const cv::Vec3b bgr(static_cast<std::uint8_t>(color[0]), static_cast<std::uint8_t>(color[1]),
                      static_cast<std::uint8_t>(color[2]));
  int count = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) count += image.at<cv::Vec3b>(y, x) == bgr ? 1 : 0;
  }
  return count;
}

PlotSpec twoSeries() {
  PlotSpec spec;
  spec.title = "correct vs alpha";
  spec.xLabel = "alpha";
  spec.yLabel = "correct";
  spec.width = 500;
  spec.height = 320;
  spec.series.push_back({"fused", {0.0, 0.25, 0.5, 0.75, 1.0}, {0.80, 0.90, 0.95, 0.93, 0.70}, cv::Scalar(0, 0, 255), {}});
  spec.series.push_back({"stereo", {0.0, 0.5, 1.0}, {0.60, 0.62, 0.61}, cv::Scalar(255, 0, 0), {}});
  return spec;
}

TEST(LinePlot, HasTheRequestedSizeAndTheSeriesColors) {
  const cv::Mat plot = linePlot(twoSeries());
  ASSERT_EQ(plot.type(), CV_8UC3);
  EXPECT_EQ(plot.cols, 500);
  EXPECT_EQ(plot.rows, 320);
  EXPECT_GT(countColor(plot, cv::Scalar(0, 0, 255)), 50);
  EXPECT_GT(countColor(plot, cv::Scalar(255, 0, 0)), 50);
  EXPECT_GT(countColor(plot, cv::Scalar(255, 255, 255)), plot.total() / 2);  // white background
}

TEST(LinePlot, DrawsALegendTopRight) {
  const cv::Mat plot = linePlot(twoSeries());
  // Inside the plot area's top-right corner (the frame and title lie outside this window);
  // the data there is colored, never dark, so dark pixels are the legend's text.
  const cv::Mat corner = plot(cv::Rect(plot.cols - 150, 44, 120, 40));
  int dark = 0;
  for (int y = 0; y < corner.rows; ++y) {
    for (int x = 0; x < corner.cols; ++x) {
      const cv::Vec3b p = corner.at<cv::Vec3b>(y, x);
      dark += (p[0] < 100 && p[1] < 100 && p[2] < 100) ? 1 : 0;
    }
  }
  EXPECT_GT(dark, 20);
}

TEST(LinePlot, FixedRangeAndOddInputDoNotFail) {
  PlotSpec spec = twoSeries();
  spec.fixedY = true;
  spec.yMin = 0.75;  // part of the data lies below: clipped at the axis
  spec.yMax = 1.0;
  spec.series[0].y[2] = std::numeric_limits<double>::quiet_NaN();  // a gap in the line
  EXPECT_EQ(linePlot(spec).size(), cv::Size(500, 320));
  EXPECT_EQ(linePlot(PlotSpec{}).size(), cv::Size(640, 420));  // no series: axes only
}

TEST(LinePlot, RejectsMismatchedSeries) {
  PlotSpec spec = twoSeries();
  spec.series[1].y.pop_back();
  EXPECT_THROW(linePlot(spec), std::invalid_argument);
}

// Labels are optional, one per point: they add text (anti-aliased, so counted as changed pixels).
TEST(LinePlot, DrawsPointLabelsAndRejectsAMismatchedCount) {
  PlotSpec spec = twoSeries();
  const cv::Mat plain = linePlot(spec);
  spec.series[1].labels = {"0.0", "", "0.9"};
  cv::Mat changed;
  cv::absdiff(linePlot(spec), plain, changed);
  EXPECT_GT(cv::countNonZero(changed.reshape(1)), 20);
  spec.series[1].labels.pop_back();
  EXPECT_THROW(linePlot(spec), std::invalid_argument);
}

TEST(Hconcat, PadsToTheTallest) {
  const cv::Mat a(30, 20, CV_8UC3, cv::Scalar(0, 0, 0));
  const cv::Mat b(50, 10, CV_8UC1, cv::Scalar(0));
  const cv::Mat joined = hconcat({a, b});
  EXPECT_EQ(joined.size(), cv::Size(30, 50));
  EXPECT_EQ(joined.at<cv::Vec3b>(40, 5), cv::Vec3b(255, 255, 255));  // padding below a
}

// ---------------------------------------------------------------------------------------------
// Pictures

TEST(ErrorMap, UsesTheKittiLogColors) {
  // Pixel 0: error 0.1 px; 1: 2 px; 2: no estimate; 3: no GT.
  std::vector<std::int16_t> estimate = {10 * kDisparityScale, 12 * kDisparityScale, kInvalidDisparity,
                                        10 * kDisparityScale};
  std::vector<float> gt = {10.1f, 10.0f, 10.0f, 0.0f};
  const cv::Mat map = errorMap(ImageView<const std::int16_t>(estimate.data(), 4, 1),
                               ImageView<const float>(gt.data(), 4, 1));
  ASSERT_EQ(map.type(), CV_8UC3);
  ASSERT_EQ(map.size(), cv::Size(4, 1));
  EXPECT_EQ(map.at<cv::Vec3b>(0, 0), cv::Vec3b(149, 54, 49));    // RGB (49, 54, 149), [0, 0.1875)
  EXPECT_EQ(map.at<cv::Vec3b>(0, 1), cv::Vec3b(248, 243, 224));  // RGB (224, 243, 248), [1.5, 3)
  EXPECT_EQ(map.at<cv::Vec3b>(0, 2), cv::Vec3b(38, 0, 165));     // RGB (165, 0, 38), the largest
  EXPECT_EQ(map.at<cv::Vec3b>(0, 3), cv::Vec3b(0, 0, 0));
}

TEST(ErrorMap, BinEdgesAndSizeCheck) {
  EXPECT_EQ(errorColor(0.0), cv::Vec3b(149, 54, 49));
  EXPECT_EQ(errorColor(3.0), cv::Vec3b(144, 224, 254));  // 3 px opens the [3, 6) bin
  EXPECT_EQ(errorColor(47.9), cv::Vec3b(39, 48, 215));
  EXPECT_EQ(errorColor(48.0), cv::Vec3b(38, 0, 165));
  std::vector<std::int16_t> estimate(4, 0);
  std::vector<float> gt(6, 1.0f);
  EXPECT_THROW(errorMap(ImageView<const std::int16_t>(estimate.data(), 4, 1),
                        ImageView<const float>(gt.data(), 6, 1)),
               std::invalid_argument);
}

TEST(Labelled, AddsADarkBarWithText) {
  const cv::Mat image(40, 200, CV_8UC1, cv::Scalar(128));
  const cv::Mat result = labelled(image, "fused, alpha 0.5");
  ASSERT_EQ(result.type(), CV_8UC3);
  EXPECT_EQ(result.cols, 200);
  ASSERT_GT(result.rows, 40);
  const int bar = result.rows - 40;
  EXPECT_EQ(result.at<cv::Vec3b>(result.rows - 1, 0), cv::Vec3b(128, 128, 128));  // image below the bar
  int bright = 0;
  for (int y = 0; y < bar; ++y) {
    for (int x = 0; x < result.cols; ++x) bright += result.at<cv::Vec3b>(y, x)[0] > 200 ? 1 : 0;
  }
  EXPECT_GT(bright, 20);  // the text
  EXPECT_LT(result.at<cv::Vec3b>(0, result.cols - 1)[0], 80);  // the bar is dark
}

TEST(Stack, SumsHeightsAndMatchesWidths) {
  const cv::Mat a(30, 100, CV_8UC3, cv::Scalar(1, 2, 3));
  const cv::Mat b(20, 100, CV_8UC1, cv::Scalar(9));
  const cv::Mat c(40, 200, CV_8UC3, cv::Scalar(7, 7, 7));  // twice as wide: scaled to 100 x 20
  const cv::Mat stacked = stack({a, b, c});
  EXPECT_EQ(stacked.size(), cv::Size(100, 30 + 20 + 20));
  EXPECT_EQ(stacked.at<cv::Vec3b>(35, 50), cv::Vec3b(9, 9, 9));
  EXPECT_TRUE(stack({}).empty());
}

// ---------------------------------------------------------------------------------------------
// writeFramePictures

TEST(FramePictures, HalfSizeQuantisedAndSmallEvenForNoisyMaps) {
  // A KITTI-sized frame whose stereo-only result is pure noise (the worst case for PNG), under
  // a smooth left image.
  constexpr int kW = 1242;
  constexpr int kH = 375;
  EvalFrame frame;
  frame.dataset = "kitti2015";
  frame.name = "000000_10";
  frame.leftColor = cv::Mat(kH, kW, CV_8UC3);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) frame.leftColor.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(x % 256), static_cast<std::uint8_t>(y % 256), 90);
  }
  frame.groundTruth = Image<float>(kW, kH, 0.0f);
  for (int y = kH / 3; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) frame.groundTruth(x, y) = 5.0f + 0.1f * static_cast<float>(y);
  }
  std::mt19937 random(7);
  std::uniform_int_distribution<int> noise(0, 128 * kDisparityScale);
  Image<std::int16_t> stereo(kW, kH);
  Image<std::int16_t> fused(kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      stereo(x, y) = static_cast<std::int16_t>(noise(random));
      fused(x, y) = static_cast<std::int16_t>(std::lround((5.0 + 0.1 * y) * kDisparityScale));
    }
  }
  const std::vector<std::pair<Method, Image<std::int16_t>>> disparities{
      {Method{MethodKind::StereoSgm, 0.0}, stereo}, {Method{MethodKind::FusedSgm, kPaperAlpha}, fused}};
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("lidar_sgm_frame_pictures_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  writeFramePictures(dir.string(), frame, disparities);

  for (const std::string name : {"kitti2015_000000_10.png", "kitti2015_000000_10_stereo_vs_fused.png"}) {
    const std::filesystem::path path = dir / name;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const cv::Mat picture = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(picture.type(), CV_8UC3) << name;
    EXPECT_EQ(picture.cols, kW / 2) << name;
    EXPECT_LT(std::filesystem::file_size(path), 500u * 1024u) << name;
    std::set<int> values;  // 32 levels per channel
    for (int y = 0; y < picture.rows; ++y) {
      for (int x = 0; x < picture.cols; ++x) {
        for (int c = 0; c < 3; ++c) values.insert(picture.at<cv::Vec3b>(y, x)[c]);
      }
    }
    EXPECT_LE(values.size(), 32u) << name;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
