// SGMDensification on two real KITTI frames (../shared/data/kitti_stereo_lidar_calib_nogt):
// density, frustum, colors and how well the dense result keeps the LiDAR's own depths.
// There is no ground truth for these frames; the scan itself is the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "common/test_data.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/pcl_image.hpp"
#include "lidar_sgm/pcl/impl/sgm_densification.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace {

const char* const kFolder = "kitti_stereo_lidar_calib_nogt";
constexpr double kMaxDepth = 80.0;  // SGMDensification's default

using Densifier = SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>;

struct Frame {
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan;
  geometry::StereoCalibration calibration;  ///< as read: no image size (KITTI object format)
  cv::Mat left;                             ///< BGR
  cv::Mat right;

  /// The calibration with the image size taken from the image, as the class completes it.
  geometry::StereoCalibration sized() const {
    geometry::StereoCalibration c = calibration;
    c.width = left.cols;
    c.height = left.rows;
    return c;
  }
};

Frame loadFrame(const std::string& name) {
  const std::string root = test::sharedDataRoot() + "/" + kFolder + "/";
  Frame f;
  f.scan.reset(new pcl::PointCloud<pcl::PointXYZI>(io::readCloud(root + "velodyne/" + name + ".bin")));
  f.calibration = io::readCalibration(root + "calib/" + name + ".txt");
  f.left = io::readColorImage(root + "image_2/" + name + ".png");
  f.right = io::readColorImage(root + "image_3/" + name + ".png");
  return f;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(q * static_cast<double>(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

/// How the dense disparity reproduces the projected scan's own depths.
struct DepthAgreement {
  std::size_t samples = 0;
  double validShare = 0;  ///< samples whose pixel has a dense disparity
  double median = 0;      ///< |z_dense - z_sample| [m], z_sample from the sample's x16 disparity
  double p90 = 0;
  double medianToPoint = 0;  ///< against the exact depth of the LiDAR point (x16 rounding included)
  double p90ToPoint = 0;
};

DepthAgreement depthAgreement(const Densifier& sgm, const Frame& frame) {
  const geometry::StereoCalibration c = frame.sized();
  const geometry::ProjectedLidar& projected = sgm.getProjectedLidar();
  const Image<std::int16_t>& dense = sgm.getDisparityImage();
  std::vector<double> errors;
  std::vector<double> errorsToPoint;
  DepthAgreement a;
  a.samples = projected.samples.size();
  for (std::size_t i = 0; i < projected.samples.size(); ++i) {
    const LidarSample& s = projected.samples[i];
    const std::int16_t d16 = dense(s.x, s.y);
    if (d16 == kInvalidDisparity || d16 <= 0) continue;
    const double z = c.focalBaseline() / (d16 / 16.0);
    const double zSample = c.focalBaseline() / (s.disparity16 / 16.0);
    const pcl::PointXYZI& p = (*frame.scan)[projected.sourceIndex[i]];
    const double zPoint = (c.T_cam_lidar * Eigen::Vector3d(p.x, p.y, p.z)).z();
    errors.push_back(std::abs(z - zSample));
    errorsToPoint.push_back(std::abs(z - zPoint));
  }
  a.validShare = a.samples ? static_cast<double>(errors.size()) / static_cast<double>(a.samples) : 0.0;
  a.median = percentile(errors, 0.5);
  a.p90 = percentile(errors, 0.9);
  a.medianToPoint = percentile(errorsToPoint, 0.5);
  a.p90ToPoint = percentile(errorsToPoint, 0.9);
  return a;
}

std::string describe(const DepthAgreement& a) {
  char text[300];
  std::snprintf(text, sizeof text,
                "depth vs sample: median %.4f m, p90 %.4f m; vs exact point depth: median %.4f m, p90 %.4f m; "
                "%.2f %% of %zu samples have a dense disparity",
                a.median, a.p90, a.medianToPoint, a.p90ToPoint, 100.0 * a.validShare, a.samples);
  return text;
}

void report(::testing::Test& test, const std::string& label, const Densifier& sgm, std::size_t scan,
            std::size_t output, const DepthAgreement& a) {
  const DensificationTimings& t = sgm.getTimings();
  char text[400];
  std::snprintf(text, sizeof text,
                "%s: scan %zu points, %zu kept in the image, output %zu points (%.1fx); project %.1f ms, match %.1f "
                "ms, reproject %.1f ms",
                label.c_str(), scan, sgm.getProjectedLidar().stats.kept, output,
                static_cast<double>(output) / static_cast<double>(sgm.getProjectedLidar().stats.kept), t.project,
                t.match, t.reproject);
  std::cout << "[ FIGURES  ] " << text << "\n[ FIGURES  ] " << label << ": " << describe(a) << std::endl;
  test.RecordProperty(label + "_counts", text);
  test.RecordProperty(label + "_depth", describe(a));
}

void expectDepthsPreserved(const DepthAgreement& a) {
  EXPECT_GT(a.validShare, 0.5) << describe(a);
  EXPECT_LT(a.median, 0.05) << describe(a);
}

class KittiFrames : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!test::haveSharedData(kFolder)) {
      GTEST_SKIP() << "no " << test::sharedDataRoot() << "/" << kFolder << " (third-party KITTI data)";
    }
  }
};

TEST_P(KittiFrames, FusedDensificationIsDenseInsideTheFrustumColoredAndKeepsLidarDepths) {
  const Frame frame = loadFrame(GetParam());
  const geometry::StereoCalibration c = frame.sized();
  ASSERT_EQ(frame.left.size(), frame.right.size());

  Densifier sgm;
  sgm.setInputCloud(frame.scan);
  sgm.setCalibration(frame.calibration);
  sgm.setStereoPair(io::toPclImage(frame.left), io::toPclImage(frame.right));
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  ASSERT_EQ(sgm.getLastError(), "");
  EXPECT_EQ(sgm.getLastMode(), MatchMode::Fused);
  EXPECT_EQ(sgm.getCalibration().width, 0) << "the class keeps the calibration it was given";

  // Density: at least 5x the scan points that project into the image.
  const std::size_t kept = sgm.getProjectedLidar().stats.kept;
  ASSERT_GT(kept, 10000u);
  EXPECT_GE(dense.size(), 5 * kept);
  EXPECT_EQ(dense.height, 1u);
  EXPECT_EQ(dense.width, dense.size());

  // Frustum: in front of the camera, inside the image, no deeper than the 80 m default.
  const double W = c.width;
  const double H = c.height;
  std::size_t outside = 0;
  for (const pcl::PointXYZRGB& q : dense) {
    const Eigen::Vector3d p = c.T_cam_lidar * Eigen::Vector3d(q.x, q.y, q.z);
    const double u = c.fx() * p.x() / p.z() + c.cx();
    const double v = c.fy() * p.y() / p.z() + c.cy();
    const bool inside = std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && p.z() > 0.0 &&
                        p.z() <= kMaxDepth + 1e-3 && u >= -0.5 - 1e-3 && u < W - 0.5 + 1e-3 && v >= -0.5 - 1e-3 &&
                        v < H - 0.5 + 1e-3;
    if (!inside && ++outside <= 5) {
      ADD_FAILURE() << "point (" << q.x << ", " << q.y << ", " << q.z << ") -> camera z " << p.z() << ", pixel (" << u
                    << ", " << v << ") is outside the frustum";
    }
  }
  EXPECT_EQ(outside, 0u);

  const DepthAgreement agreement = depthAgreement(sgm, frame);
  report(*this, GetParam() + "_fused", sgm, frame.scan->size(), dense.size(), agreement);
  expectDepthsPreserved(agreement);

  // Organized: the same points at their pixels, colored from the left image (BGR in OpenCV).
  sgm.setKeepOrganized(true);
  pcl::PointCloud<pcl::PointXYZRGB> organized;
  sgm.filter(organized);
  ASSERT_EQ(sgm.getLastError(), "");
  ASSERT_EQ(organized.width, static_cast<std::uint32_t>(c.width));
  ASSERT_EQ(organized.height, static_cast<std::uint32_t>(c.height));
  EXPECT_FALSE(organized.is_dense);
  std::size_t validPoints = 0;
  std::size_t wrongColor = 0;
  std::size_t notSame = 0;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const pcl::PointXYZRGB& q = organized.at(x, y);
      if (!std::isfinite(q.x)) continue;
      const cv::Vec3b bgr = frame.left.at<cv::Vec3b>(y, x);
      if (q.r != bgr[2] || q.g != bgr[1] || q.b != bgr[0]) {
        if (++wrongColor <= 5) {
          ADD_FAILURE() << "pixel (" << x << ", " << y << "): rgb " << int{q.r} << " " << int{q.g} << " " << int{q.b}
                        << ", image " << int{bgr[2]} << " " << int{bgr[1]} << " " << int{bgr[0]};
        }
      }
      // The unorganized run gave the valid points in row-major order.
      if (validPoints < dense.size()) {
        const pcl::PointXYZRGB& u = dense[validPoints];
        notSame += u.x == q.x && u.y == q.y && u.z == q.z && u.rgba == q.rgba ? 0 : 1;
      }
      ++validPoints;
    }
  }
  EXPECT_EQ(wrongColor, 0u);
  EXPECT_EQ(validPoints, dense.size()) << "organized and unorganized runs disagree";
  EXPECT_EQ(notSame, 0u);
}

INSTANTIATE_TEST_SUITE_P(Kitti, KittiFrames, ::testing::Values("stereo_rcnn_demo", "densedepthmap_0000000001"),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

TEST(KittiFramesLidarOnly, ColorImageOnlyKeepsLidarDepths) {
  if (!test::haveSharedData(kFolder)) GTEST_SKIP() << "no " << test::sharedDataRoot() << "/" << kFolder;
  const std::string name = "stereo_rcnn_demo";
  const Frame frame = loadFrame(name);
  Densifier sgm;
  sgm.setInputCloud(frame.scan);
  sgm.setCalibration(frame.calibration);
  sgm.setColorImage(io::toPclImage(frame.left));
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  ASSERT_EQ(sgm.getLastError(), "");
  EXPECT_EQ(sgm.getLastMode(), MatchMode::LidarOnly);
  const std::size_t kept = sgm.getProjectedLidar().stats.kept;
  EXPECT_GE(dense.size(), 5 * kept);
  ASSERT_EQ(sgm.getDisparityImage().width(), frame.left.cols);
  ASSERT_EQ(sgm.getDisparityImage().height(), frame.left.rows);

  const DepthAgreement agreement = depthAgreement(sgm, frame);
  report(*this, name + "_lidar_only", sgm, frame.scan->size(), dense.size(), agreement);
  expectDepthsPreserved(agreement);
}

}  // namespace
}  // namespace lidar_sgm

// The PCL class converts pcl::RGB images to gray itself; the tools read gray through OpenCV.
// They must agree exactly, or the same pair would match differently by the way it was given.
TEST(PclImageGray, EqualsOpenCvsBgrToGrayForEveryColor) {
  cv::Mat bgr(4096, 4096, CV_8UC3);
  for (int i = 0; i < 4096 * 4096; ++i) {
    bgr.at<cv::Vec3b>(i / 4096, i % 4096) =
        cv::Vec3b(static_cast<std::uint8_t>(i & 255), static_cast<std::uint8_t>((i >> 8) & 255),
                  static_cast<std::uint8_t>((i >> 16) & 255));
  }
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  long mismatches = 0;
  for (int i = 0; i < 4096 * 4096; ++i) {
    const cv::Vec3b c = bgr.at<cv::Vec3b>(i / 4096, i % 4096);
    mismatches += lidar_sgm::detail::grayFromRgb(c[2], c[1], c[0]) != gray.at<std::uint8_t>(i / 4096, i % 4096);
  }
  EXPECT_EQ(mismatches, 0);
}
