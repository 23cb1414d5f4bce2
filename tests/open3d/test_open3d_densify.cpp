// densify() on Open3D data gives the Densifier's points, bit for bit, in every mode, and refuses
// bad input with a message naming the problem.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/open3d/densify.hpp"
#include "open3d/open3d_test_helpers.hpp"

namespace lidar_sgm {
namespace {

using Open3dImage = ::open3d::geometry::Image;
using Open3dCloud = ::open3d::geometry::PointCloud;

constexpr double kWallDisparity = 10.0;  // smallRig: f*b = 50 px*m, so the wall is at 5 m

struct Scene {
  geometry::StereoCalibration c = test::smallRig();
  test::SyntheticStereo stereo = test::makeStereo(c.width, c.height, [](double, double) { return kWallDisparity; });
  Open3dCloud scan = test::wallScan(c, c.fx() * c.baseline / kWallDisparity);
  Parameters parameters;
  Scene() { parameters.numDisparities = 32; }

  std::vector<Eigen::Vector3f> points() const {
    std::vector<Eigen::Vector3f> p;
    for (const Eigen::Vector3d& q : scan.points_) p.push_back(q.cast<float>());
    return p;
  }
  Densifier densifier() const {
    Densifier d;
    d.setCalibration(c);
    d.setParameters(parameters);
    return d;
  }
};

void expectSamePoints(const geometry::DenseCloud& expected, const Open3dCloud& actual) {
  ASSERT_GT(expected.size(), 0u);
  ASSERT_EQ(actual.points_.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    // float -> double -> float is exact: bit for bit the Densifier's coordinates.
    const Eigen::Vector3f p = actual.points_[i].cast<float>();
    ASSERT_EQ(p.x(), expected.points[i].x()) << i;
    ASSERT_EQ(p.y(), expected.points[i].y()) << i;
    ASSERT_EQ(p.z(), expected.points[i].z()) << i;
  }
}

template <typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Open3dDensify, FusedGivesTheDensifiersPointsAndColorsFromTheLeftImage) {
  const Scene s;
  Densifier reference = s.densifier();
  reference.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  const geometry::DenseCloud& expected = reference.run(s.points());
  ASSERT_EQ(reference.lastMode(), MatchMode::Fused);

  Open3dImage left = test::open3dRgb(s.stereo.left);
  const Open3dImage right = test::open3dRgb(s.stereo.right);
  // One red pixel in the left image: gray matching barely sees it, the colors must.
  const geometry::PixelIndex red = expected.pixels[expected.size() / 2];
  std::uint8_t* pixel = left.PointerAt<std::uint8_t>(red.x, red.y, 0);
  pixel[0] = 255;
  pixel[1] = 0;
  pixel[2] = 0;
  reference.setStereoPair(Open3dGray(left).view(), Open3dGray(right).view());
  const geometry::DenseCloud& expectedRed = reference.run(s.points());

  const auto dense = densify(s.scan, s.c, &left, &right, s.parameters);
  ASSERT_TRUE(dense);
  expectSamePoints(expectedRed, *dense);
  ASSERT_TRUE(dense->HasColors());
  int reds = 0;
  for (std::size_t i = 0; i < dense->colors_.size(); ++i) {
    const Eigen::Vector3d& color = dense->colors_[i];
    const geometry::PixelIndex px = expectedRed.pixels[i];
    if (px.x == red.x && px.y == red.y) {
      EXPECT_EQ(color, Eigen::Vector3d(1.0, 0.0, 0.0));
      ++reds;
    } else {
      // The rest is gray, in [0, 1]: the left image's level / 255.
      EXPECT_EQ(color.x(), s.stereo.left(px.x, px.y) / 255.0) << i;
      EXPECT_EQ(color.x(), color.z()) << i;
    }
  }
  EXPECT_EQ(reds, 1);
}

TEST(Open3dDensify, SixteenBitGrayPairMatchesAsEightBit) {
  const Scene s;
  Densifier reference = s.densifier();
  reference.setStereoPair(s.stereo.left.view(), s.stereo.right.view());
  const geometry::DenseCloud& expected = reference.run(s.points());
  Open3dImage left16 = test::open3dImage(s.c.width, s.c.height, 1, 2);
  Open3dImage right16 = test::open3dImage(s.c.width, s.c.height, 1, 2);
  for (int y = 0; y < s.c.height; ++y) {
    for (int x = 0; x < s.c.width; ++x) {
      *left16.PointerAt<std::uint16_t>(x, y) = static_cast<std::uint16_t>(s.stereo.left(x, y) * 257);
      *right16.PointerAt<std::uint16_t>(x, y) = static_cast<std::uint16_t>(s.stereo.right(x, y) * 257);
    }
  }
  const auto dense = densify(s.scan, s.c, &left16, &right16, s.parameters);
  expectSamePoints(expected, *dense);
  // Colors from 16 bit: v / 257, the 8-bit levels again.
  ASSERT_TRUE(dense->HasColors());
  const geometry::PixelIndex px = expected.pixels[0];
  EXPECT_EQ(dense->colors_[0].y(), s.stereo.left(px.x, px.y) / 255.0);
}

TEST(Open3dDensify, LidarOnlyWithAndWithoutALeftImage) {
  const Scene s;
  Densifier reference = s.densifier();
  const geometry::DenseCloud& expected = reference.run(s.points());
  ASSERT_EQ(reference.lastMode(), MatchMode::LidarOnly);

  const auto plain = densify(s.scan, s.c, nullptr, nullptr, s.parameters);
  expectSamePoints(expected, *plain);
  EXPECT_FALSE(plain->HasColors());

  const Open3dImage left = test::open3dRgb(s.stereo.left);
  const auto colored = densify(s.scan, s.c, &left, nullptr, s.parameters);
  expectSamePoints(expected, *colored);
  EXPECT_TRUE(colored->HasColors());
}

TEST(Open3dDensify, AReusedDensifierDropsThePreviousFramesImages) {
  const Scene s;
  Densifier densifier = s.densifier();
  const Open3dImage left = test::open3dRgb(s.stereo.left);
  const Open3dImage right = test::open3dRgb(s.stereo.right);
  densify(densifier, s.scan, &left, &right);
  EXPECT_EQ(densifier.lastMode(), MatchMode::Fused);
  const auto second = densify(densifier, s.scan);
  EXPECT_EQ(densifier.lastMode(), MatchMode::LidarOnly);
  EXPECT_FALSE(second->HasColors());
  EXPECT_FALSE(densifier.hasColorImage());
}

TEST(Open3dDensify, BadInputThrowsNamingTheProblem) {
  const Scene s;
  const Open3dImage left = test::open3dRgb(s.stereo.left);
  const Open3dImage right = test::open3dRgb(s.stereo.right);

  EXPECT_NE(errorOf([&] { densify(Open3dCloud(), s.c, &left, &right, s.parameters); }).find("the scan (Open3D point cloud) is empty"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { densify(s.scan, s.c, nullptr, &right, s.parameters); }).find("needs the left one"),
            std::string::npos);
  // Wrong channels, wrong bytes per channel.
  const Open3dImage twoChannels = test::open3dImage(s.c.width, s.c.height, 2, 1);
  EXPECT_NE(errorOf([&] { densify(s.scan, s.c, &twoChannels, &right, s.parameters); }).find("2 channel(s) of 1 byte(s)"),
            std::string::npos);
  const Open3dImage floats = test::open3dImage(s.c.width, s.c.height, 1, 4);
  EXPECT_NE(errorOf([&] { densify(s.scan, s.c, &floats, nullptr, s.parameters); }).find("1 channel(s) of 4 byte(s)"),
            std::string::npos);
  // A pair of two formats.
  const Open3dImage gray = test::open3dImage(s.c.width, s.c.height, 1, 1, 128);
  EXPECT_NE(errorOf([&] { densify(s.scan, s.c, &left, &gray, s.parameters); }).find("differ in format"),
            std::string::npos);
  // Sizes: the pair's against each other, the images' against the calibration's.
  const Open3dImage narrow = test::open3dImage(s.c.width - 1, s.c.height, 3, 1);
  const std::string pairSizes = errorOf([&] { densify(s.scan, s.c, &left, &narrow, s.parameters); });
  EXPECT_NE(pairSizes.find(std::to_string(s.c.width - 1)), std::string::npos) << pairSizes;
  const Open3dImage narrowLeft = test::open3dImage(s.c.width - 1, s.c.height, 3, 1);
  const std::string colorSize = errorOf([&] { densify(s.scan, s.c, &narrowLeft, nullptr, s.parameters); });
  EXPECT_NE(colorSize.find("but the calibration is for"), std::string::npos) << colorSize;
}

}  // namespace
}  // namespace lidar_sgm
