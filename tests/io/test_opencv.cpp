// io::toOpenCvDisparity against cv::StereoSGBM itself: the invalid value it writes is the one
// openCvInvalidDisparity16 names, and valid disparities keep their x16 values.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "lidar_sgm/io/opencv.hpp"

namespace lidar_sgm {
namespace {

TEST(ToOpenCvDisparity, InvalidBecomesStereoSGBMsInvalidValue) {
  // A textured pair shifted by 8 px: SGBM leaves the left border (no match possible) invalid.
  cv::Mat left(64, 96, CV_8UC1);
  cv::randu(left, 0, 255);
  cv::Mat right(left.size(), CV_8UC1, cv::Scalar(0));
  left(cv::Rect(8, 0, 88, 64)).copyTo(right(cv::Rect(0, 0, 88, 64)));
  for (const int minDisparity : {0, 4, -3}) {
    SCOPED_TRACE(minDisparity);
    cv::Mat sgbm;
    cv::StereoSGBM::create(minDisparity, 16, 5)->compute(left, right, sgbm);
    ASSERT_EQ(sgbm.type(), CV_16SC1);
    double lowest = 0.0;
    cv::minMaxLoc(sgbm, &lowest);
    ASSERT_EQ(lowest, openCvInvalidDisparity16(minDisparity)) << "OpenCV's invalid value is not the documented one";

    // Ours: the same values where valid, kInvalidDisparity elsewhere.
    Image<std::int16_t> ours(sgbm.cols, sgbm.rows);
    for (int y = 0; y < sgbm.rows; ++y) {
      for (int x = 0; x < sgbm.cols; ++x) {
        const std::int16_t v = sgbm.at<std::int16_t>(y, x);
        ours(x, y) = v == lowest ? kInvalidDisparity : v;
      }
    }
    const cv::Mat back = io::toOpenCvDisparity(ours.view(), minDisparity);
    ASSERT_EQ(back.type(), CV_16SC1);
    EXPECT_EQ(cv::countNonZero(back != sgbm), 0);
  }
}

TEST(ToOpenCvDisparity, KeepsPaddedStridesAndValues) {
  std::vector<std::int16_t> pixels(5 * 8, 7);  // 5x3 image in rows of 8
  pixels[8 + 1] = kInvalidDisparity;
  pixels[2 * 8 + 4] = 400;
  const cv::Mat m = io::toOpenCvDisparity(ImageView<const std::int16_t>(pixels.data(), 5, 3, 8), 2);
  ASSERT_EQ(m.cols, 5);
  ASSERT_EQ(m.rows, 3);
  EXPECT_EQ(m.at<std::int16_t>(1, 1), 16);  // (2 - 1) * 16
  EXPECT_EQ(m.at<std::int16_t>(2, 4), 400);
  EXPECT_EQ(m.at<std::int16_t>(0, 0), 7);
  EXPECT_EQ(cv::countNonZero(m == 7), 13);
}

}  // namespace
}  // namespace lidar_sgm
