// The cv::Mat overloads of sgm_densification_opencv.hpp give what the PCL/core overloads give.
#include <gtest/gtest.h>

#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <pcl/point_types.h>

#include "common/synthetic_stereo.hpp"
#include "pcl/pcl_test_helpers.hpp"
#include "lidar_sgm/pcl/sgm_densification_opencv.hpp"

namespace lidar_sgm {
namespace {

using Sgm = SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>;

struct Fixture {
  geometry::StereoCalibration c = test::pclRig();
  test::SyntheticStereo stereo = test::makeStereo(c.width, c.height, [](double x, double) { return 20.0 + x / 16.0; });
  cv::Mat left8 = cv::Mat(c.height, c.width, CV_8UC1, stereo.left.data()).clone();
  cv::Mat right8 = cv::Mat(c.height, c.width, CV_8UC1, stereo.right.data()).clone();

  /// A frame with the pair given by `give`; its disparity.
  template <typename Give>
  Image<std::int16_t> disparity(Give give, pcl::PointCloud<pcl::PointXYZRGB>* out = nullptr) const {
    Sgm sgm;
    sgm.setInputCloud(test::wallScan<pcl::PointXYZI>(c));
    sgm.setCalibration(c);
    sgm.setNumDisparities(64);
    give(sgm);
    pcl::PointCloud<pcl::PointXYZRGB> dense;
    sgm.filter(dense);
    EXPECT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
    EXPECT_EQ(sgm.getLastMode(), MatchMode::Fused);
    if (out) *out = dense;
    return sgm.getDisparityImage();
  }
};

void expectSame(const Image<std::int16_t>& a, const Image<std::int16_t>& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) ASSERT_EQ(a(x, y), b(x, y)) << x << "," << y;
  }
}

TEST(SGMDensificationOpenCV, GrayAndColorMatsMatchAsTheViewsAndPclImagesDo) {
  const Fixture f;
  const Image<std::int16_t> reference =
      f.disparity([&](Sgm& s) { s.setStereoPair(f.stereo.left.view(), f.stereo.right.view()); });
  expectSame(f.disparity([&](Sgm& s) { setStereoPair(s, f.left8, f.right8); }), reference);

  // 16 bit: the same order of intensities, so the same census.
  cv::Mat left16, right16;
  f.left8.convertTo(left16, CV_16U, 257.0);
  f.right8.convertTo(right16, CV_16U, 257.0);
  expectSame(f.disparity([&](Sgm& s) { setStereoPair(s, left16, right16); }), reference);

  // BGR: gray by BGR2GRAY (gray in, gray out), and the left one colors the points.
  cv::Mat leftBgr, rightBgr;
  cv::cvtColor(f.left8, leftBgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(f.right8, rightBgr, cv::COLOR_GRAY2BGR);
  leftBgr.at<cv::Vec3b>(50, 40) = cv::Vec3b(0, 0, 255);  // one red pixel, to see the color's origin
  pcl::PointCloud<pcl::PointXYZRGB> colored;
  f.disparity([&](Sgm& s) { setStereoPair(s, leftBgr, rightBgr); }, &colored);
  ASSERT_FALSE(colored.empty());
  int red = 0;
  for (const auto& p : colored) red += p.r == 255 && p.g == 0 && p.b == 0 ? 1 : 0;
  EXPECT_EQ(red, 1);

  // A 16-bit BGR pair is matched in 16-bit gray.
  cv::Mat leftBgr16, rightBgr16;
  cv::cvtColor(left16, leftBgr16, cv::COLOR_GRAY2BGR);
  cv::cvtColor(right16, rightBgr16, cv::COLOR_GRAY2BGR);
  expectSame(f.disparity([&](Sgm& s) { setStereoPair(s, leftBgr16, rightBgr16); }), reference);
}

TEST(SGMDensificationOpenCV, ColorImageFromAMat) {
  const Fixture f;
  cv::Mat bgr(f.c.height, f.c.width, CV_8UC3, cv::Scalar(1, 2, 3));  // B, G, R
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  f.disparity(
      [&](Sgm& s) {
        setColorImage(s, bgr);
        setStereoPair(s, f.left8, f.right8);  // a gray pair does not override the color image
      },
      &dense);
  ASSERT_FALSE(dense.empty());
  for (const auto& p : dense) {
    ASSERT_EQ(p.r, 3);
    ASSERT_EQ(p.g, 2);
    ASSERT_EQ(p.b, 1);
  }
}

TEST(SGMDensificationOpenCV, UnsupportedTypesThrowAndMixedDepthsAreReportedByFilter) {
  const Fixture f;
  Sgm sgm;
  const cv::Mat floats(f.c.height, f.c.width, CV_32FC1, cv::Scalar(0));
  EXPECT_THROW(setStereoPair(sgm, floats, floats), std::invalid_argument);
  EXPECT_THROW(setColorImage(sgm, floats), std::invalid_argument);
  cv::Mat right16;
  f.right8.convertTo(right16, CV_16U, 257.0);
  sgm.setInputCloud(test::wallScan<pcl::PointXYZI>(f.c));
  sgm.setCalibration(f.c);
  setStereoPair(sgm, f.left8, right16);
  pcl::PointCloud<pcl::PointXYZRGB> dense(3, 1);
  sgm.filter(dense);
  EXPECT_TRUE(dense.empty());
  EXPECT_NE(sgm.getLastError().find("bit depth"), std::string::npos) << sgm.getLastError();
}

}  // namespace
}  // namespace lidar_sgm
