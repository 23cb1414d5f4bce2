// The cloud preview: where a point lands (worked by hand), splat size, z-buffer, colors,
// determinism, the frame conversion and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lidar_sgm/io/cloud_preview.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Only the points: no grid, no rig marker.
io::CloudPreviewOptions bareOptions() {
  io::CloudPreviewOptions o;
  o.grid = false;
  o.markRig = false;
  return o;
}

/// The projection written out from the definition (camera at (0, -h, -b), pitched down by
/// theta about x, pinhole with f = W/2 / tan(fov/2), principal point at the picture's centre).
Eigen::Vector3d handProjection(const Eigen::Vector3d& p, const io::CloudPreviewOptions& o) {
  const double theta = o.pitchDeg * kPi / 180.0;
  const double dy = p.y() + o.cameraHeight;  // below the camera (y down)
  const double dz = p.z() + o.cameraBehind;  // ahead of the camera
  const double depth = std::sin(theta) * dy + std::cos(theta) * dz;
  const double down = std::cos(theta) * dy - std::sin(theta) * dz;
  const double f = 0.5 * o.width / std::tan(0.5 * o.fieldOfViewDeg * kPi / 180.0);
  return {f * p.x() / depth + 0.5 * o.width, f * down / depth + 0.5 * o.height, depth};
}

cv::Vec3b background(const io::CloudPreviewOptions& o) {
  const cv::Mat empty = io::renderCloudPreview({Eigen::Vector3f(0.0f, 0.0f, 1e3f)}, {}, o);  // beyond maxDepth
  return empty.at<cv::Vec3b>(0, 0);
}

std::size_t pixelsOfColor(const cv::Mat& image, const cv::Vec3b& color) {
  std::size_t n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) n += image.at<cv::Vec3b>(y, x) == color ? 1 : 0;
  }
  return n;
}

TEST(CloudPreview, ProjectionMatchesTheHandWorkedOne) {
  const io::CloudPreviewOptions o;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2.0, 1.0, 30.0), Eigen::Vector3d(-7.5, -15.0, 60.0),
                                   Eigen::Vector3d(0.0, 1.65, 0.0)}) {
    const Eigen::Vector3d expected = handProjection(p, o);
    const Eigen::Vector3d got = io::projectToPreview(p, o);
    EXPECT_NEAR(got.x(), expected.x(), 1e-9) << p.transpose();
    EXPECT_NEAR(got.y(), expected.y(), 1e-9) << p.transpose();
    EXPECT_NEAR(got.z(), expected.z(), 1e-9) << p.transpose();
  }
  // A point on the virtual camera's axis, (0, sin, cos) from its centre, lands in the middle.
  const double theta = o.pitchDeg * kPi / 180.0;
  const Eigen::Vector3d axis(0.0, -o.cameraHeight + 40.0 * std::sin(theta), -o.cameraBehind + 40.0 * std::cos(theta));
  const Eigen::Vector3d centre = io::projectToPreview(axis, o);
  EXPECT_NEAR(centre.x(), o.width / 2.0, 1e-9);
  EXPECT_NEAR(centre.y(), o.height / 2.0, 1e-9);
  EXPECT_NEAR(centre.z(), 40.0, 1e-9);
}

TEST(CloudPreview, APointIsASquareSplatAtItsProjectionSizedByDistance) {
  io::CloudPreviewOptions o = bareOptions();
  o.width = 321;  // odd sizes on purpose
  o.height = 203;
  const Eigen::Vector3f p(1.5f, 1.0f, 20.0f);
  const Rgb8 red{255, 0, 0};
  const cv::Mat image = io::renderCloudPreview({p}, {red}, o);
  ASSERT_EQ(image.type(), CV_8UC3);
  ASSERT_EQ(image.cols, 321);
  ASSERT_EQ(image.rows, 203);
  const Eigen::Vector3d uvz = handProjection(p.cast<double>(), o);
  const double f = 0.5 * o.width / std::tan(0.5 * o.fieldOfViewDeg * kPi / 180.0);
  const int size = std::max(1, static_cast<int>(std::lround(o.pointSize * f / uvz.z())));
  const int x0 = static_cast<int>(std::floor(uvz.x())) - (size - 1) / 2;
  const int y0 = static_cast<int>(std::floor(uvz.y())) - (size - 1) / 2;
  const cv::Vec3b bgrRed(0, 0, 255);
  EXPECT_EQ(image.at<cv::Vec3b>(static_cast<int>(std::floor(uvz.y())), static_cast<int>(std::floor(uvz.x()))), bgrRed);
  EXPECT_EQ(pixelsOfColor(image, bgrRed), static_cast<std::size_t>(size * size));
  const cv::Rect splat(x0, y0, size, size);
  EXPECT_EQ(pixelsOfColor(image(splat), bgrRed), static_cast<std::size_t>(size * size));

  // Farther away (and nowhere near the picture's edge): a smaller square, down to one pixel.
  o.width = 960;
  o.height = 600;
  const std::size_t near = pixelsOfColor(io::renderCloudPreview({Eigen::Vector3f(0, 1, 2)}, {red}, o), bgrRed);
  const std::size_t far = pixelsOfColor(io::renderCloudPreview({Eigen::Vector3f(0, 1, 75)}, {red}, o), bgrRed);
  EXPECT_GT(near, far);
  EXPECT_EQ(far, 1u);
  o.maxSplatPx = 2;
  EXPECT_EQ(pixelsOfColor(io::renderCloudPreview({Eigen::Vector3f(0, 1, 2)}, {red}, o), bgrRed), 4u);
}

TEST(CloudPreview, TheNearestPointWinsWhateverTheOrder) {
  const io::CloudPreviewOptions o = bareOptions();
  // Two points on one ray from the virtual camera: the nearer hides the farther.
  const Eigen::Vector3f camera(0.0f, static_cast<float>(-o.cameraHeight), static_cast<float>(-o.cameraBehind));
  const Eigen::Vector3f direction = Eigen::Vector3f(3.0f, 15.0f, 45.0f).normalized();
  const Eigen::Vector3f nearPoint = camera + 30.0f * direction;
  const Eigen::Vector3f farPoint = camera + 60.0f * direction;
  const Rgb8 green{0, 255, 0};
  const Rgb8 blue{0, 0, 255};
  const Eigen::Vector3d uv = handProjection(nearPoint.cast<double>(), o);
  const cv::Point at(static_cast<int>(std::floor(uv.x())), static_cast<int>(std::floor(uv.y())));
  const cv::Mat a = io::renderCloudPreview({nearPoint, farPoint}, {green, blue}, o);
  const cv::Mat b = io::renderCloudPreview({farPoint, nearPoint}, {blue, green}, o);
  EXPECT_EQ(a.at<cv::Vec3b>(at), cv::Vec3b(0, 255, 0));
  EXPECT_EQ(b.at<cv::Vec3b>(at), cv::Vec3b(0, 255, 0));
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(CloudPreview, WithoutColorsDepthIsColorMappedAndFarPointsAreDropped) {
  io::CloudPreviewOptions o = bareOptions();
  const cv::Vec3b empty = background(o);
  const cv::Mat nearImage = io::renderCloudPreview({Eigen::Vector3f(0, 1, 5)}, {}, o);
  const cv::Mat farImage = io::renderCloudPreview({Eigen::Vector3f(0, 1, 70)}, {}, o);
  const auto colorAt = [&](const cv::Mat& image, const Eigen::Vector3f& p) {
    const Eigen::Vector3d uv = handProjection(p.cast<double>(), o);
    return image.at<cv::Vec3b>(static_cast<int>(std::floor(uv.y())), static_cast<int>(std::floor(uv.x())));
  };
  // Turbo: blue near (B > R), red far (R > B).
  const cv::Vec3b nearColor = colorAt(nearImage, {0, 1, 5});
  const cv::Vec3b farColor = colorAt(farImage, {0, 1, 70});
  EXPECT_GT(nearColor[0], nearColor[2]);
  EXPECT_GT(farColor[2], farColor[0]);
  EXPECT_NE(nearColor, empty);
  // Beyond maxDepth, non-finite, or behind the virtual camera: nothing drawn.
  o.maxDepth = 50.0;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Eigen::Vector3f> hidden{Eigen::Vector3f(0, 1, 70), Eigen::Vector3f(nan, 0, 10),
                                            Eigen::Vector3f(0, 0, -40)};
  const cv::Mat none = io::renderCloudPreview(hidden, {}, o);
  EXPECT_EQ(pixelsOfColor(none, empty), static_cast<std::size_t>(o.width * o.height));
}

TEST(CloudPreview, GridAndRigAreDrawnAndTheSameCloudGivesTheSameBytes) {
  std::vector<Eigen::Vector3f> points;
  std::vector<Rgb8> colors;
  for (int i = 0; i < 20000; ++i) {  // a wall 15-20 m up, 20-80 m ahead: a "sky curtain"
    const float t = static_cast<float>(i) / 20000.0f;
    points.emplace_back(-10.0f + 20.0f * t, -15.0f - 5.0f * std::fmod(37.0f * t, 1.0f), 20.0f + 60.0f * t);
    colors.push_back({static_cast<std::uint8_t>(i % 256), 200, 100});
  }
  const io::CloudPreviewOptions o;
  const cv::Mat a = io::renderCloudPreview(points, colors, o);
  const cv::Mat b = io::renderCloudPreview(points, colors, o);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // The curtain is in the picture, above the rig: the curtain's points at 15-20 m height stand out.
  const Eigen::Vector3d top = handProjection({0.0, -17.5, 50.0}, o);
  EXPECT_GT(top.y(), 0.0);
  EXPECT_LT(top.y(), o.height);
  // The rig marker (white) under the rig camera, the grid under the points.
  const Eigen::Vector3d rig = handProjection({0.0, o.groundBelowCamera, 0.0}, o);
  EXPECT_EQ(a.at<cv::Vec3b>(static_cast<int>(rig.y()), static_cast<int>(rig.x())), cv::Vec3b(255, 255, 255));
  const cv::Mat bare = io::renderCloudPreview(points, colors, bareOptions());
  EXPECT_NE(cv::norm(a, bare, cv::NORM_INF), 0.0);
}

TEST(CloudPreview, BadInputIsNamed) {
  const std::vector<Eigen::Vector3f> one{Eigen::Vector3f(0, 0, 10)};
  const auto expectError = [](const auto& call, const std::string& message) {
    try {
      call();
      ADD_FAILURE() << "no error, expected '" << message << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expectError([] { io::renderCloudPreview({}, {}); }, "the cloud has no points");
  expectError([&] { io::renderCloudPreview(one, {Rgb8{}, Rgb8{}}); }, "2 colors for 1 points");
  io::CloudPreviewOptions o;
  o.width = 0;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "the picture size 0x600");
  o = {};
  o.height = 10000;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "the picture size 960x10000");
  o = {};
  o.pitchDeg = 90.0;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "pitch");
  o = {};
  o.fieldOfViewDeg = 0.0;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "field of view");
  o = {};
  o.maxDepth = -1.0;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "maximum depth");
  o = {};
  o.pointSize = 0.0;
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "point size");
  o = {};
  o.cameraHeight = std::numeric_limits<double>::infinity();
  expectError([&] { io::renderCloudPreview(one, {}, o); }, "camera height");
}

TEST(CloudPreview, InputsComeIntoTheCameraFrameWithTheirPixelsColors) {
  geometry::StereoCalibration calibration;
  calibration.T_cam_lidar.linear() << 0, -1, 0, 0, 0, -1, 1, 0, 0;  // KITTI-like axes
  calibration.T_cam_lidar.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
  geometry::DenseCloud cloud;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points = {Eigen::Vector3f(10, 2, -1), Eigen::Vector3f(nan, nan, nan), Eigen::Vector3f(20, -1, 0.5f)};
  cloud.pixels = {{1, 0}, {0, 0}, {2, 1}};
  Image<Rgb8> color(3, 2);
  color(1, 0) = {10, 20, 30};
  color(2, 1) = {40, 50, 60};
  std::vector<Eigen::Vector3f> points;
  std::vector<Rgb8> colors;
  io::previewInputs(cloud, geometry::OutputFrame::Lidar, calibration, color.view(), points, colors);
  ASSERT_EQ(points.size(), 2u);
  ASSERT_EQ(colors.size(), 2u);
  // p_cam = (-y, -z, x) + t
  EXPECT_TRUE(points[0].isApprox(Eigen::Vector3f(-2 + 0.1f, 1 - 0.2f, 10 + 0.3f)));
  EXPECT_TRUE(points[1].isApprox(Eigen::Vector3f(1 + 0.1f, -0.5f - 0.2f, 20 + 0.3f)));
  EXPECT_EQ(colors[1].r, 40);
  EXPECT_EQ(colors[0].b, 30);
  io::previewInputs(cloud, geometry::OutputFrame::Camera, calibration, {}, points, colors);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_TRUE(colors.empty());
  EXPECT_EQ(points[0], cloud.points[0]);
  cloud.pixels[2] = {3, 1};
  EXPECT_THROW(io::previewInputs(cloud, geometry::OutputFrame::Camera, calibration, color.view(), points, colors),
               std::invalid_argument);
}

TEST(QuantiseColors, KeepsTheEndsAndRoundsToTheLevels) {
  cv::Mat ramp(1, 256, CV_8UC3);
  for (int i = 0; i < 256; ++i) ramp.at<cv::Vec3b>(0, i) = cv::Vec3b(static_cast<std::uint8_t>(i), 0, 255);
  const cv::Mat two = io::quantiseColors(ramp, 2);
  EXPECT_EQ(two.at<cv::Vec3b>(0, 127), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(two.at<cv::Vec3b>(0, 128), cv::Vec3b(255, 0, 255));
  const cv::Mat eighteen = io::quantiseColors(ramp, 18);  // steps of 15
  EXPECT_EQ(eighteen.at<cv::Vec3b>(0, 22)[0], 15);
  EXPECT_EQ(eighteen.at<cv::Vec3b>(0, 23)[0], 30);
  EXPECT_EQ(cv::norm(io::quantiseColors(ramp, 256), ramp, cv::NORM_INF), 0.0);
  EXPECT_THROW(io::quantiseColors(ramp, 1), std::invalid_argument);
  EXPECT_THROW(io::quantiseColors(cv::Mat(2, 2, CV_16UC1), 16), std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
