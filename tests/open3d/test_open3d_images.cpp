// Open3D images <-> lidar_sgm images: formats accepted, refused with a message naming them, and
// round trips.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "lidar_sgm/open3d/image_conversion.hpp"
#include "open3d/open3d_test_helpers.hpp"

namespace lidar_sgm {
namespace {

using test::open3dImage;

template <typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Open3dImages, GrayViewsAreViewsWithoutACopy) {
  ::open3d::geometry::Image gray8 = open3dImage(7, 5, 1, 1);
  *gray8.PointerAt<std::uint8_t>(3, 2) = 200;
  const GrayImageView v8 = grayView(gray8);
  ASSERT_FALSE(v8.gray8.empty());
  EXPECT_TRUE(v8.gray16.empty());
  EXPECT_EQ(v8.gray8.data, gray8.data_.data());
  EXPECT_EQ(v8.width(), 7);
  EXPECT_EQ(v8.height(), 5);
  EXPECT_EQ(v8.gray8(3, 2), 200);

  ::open3d::geometry::Image gray16 = open3dImage(7, 5, 1, 2);
  *gray16.PointerAt<std::uint16_t>(6, 4) = 54321;
  const GrayImageView v16 = grayView(gray16);
  ASSERT_FALSE(v16.gray16.empty());
  EXPECT_TRUE(v16.gray8.empty());
  EXPECT_EQ(v16.gray16(6, 4), 54321);
  EXPECT_EQ(v16.gray16.stride, 7);
}

TEST(Open3dImages, OtherFormatsAreRefusedNamingTheFormat) {
  const ::open3d::geometry::Image floats = open3dImage(4, 3, 1, 4);
  EXPECT_NE(errorOf([&] { grayView(floats); }).find("1 channel(s) of 4 byte(s)"), std::string::npos);
  EXPECT_NE(errorOf([&] { Open3dGray g(floats); }).find("8- or 16-bit"), std::string::npos);
  const ::open3d::geometry::Image twoChannels = open3dImage(4, 3, 2, 1);
  EXPECT_NE(errorOf([&] { toRgb8(twoChannels); }).find("2 channel(s) of 1 byte(s)"), std::string::npos);
  // A color image is no gray view: the message says what converts it.
  const ::open3d::geometry::Image rgb = open3dImage(4, 3, 3, 1);
  EXPECT_NE(errorOf([&] { grayView(rgb); }).find("Open3dGray"), std::string::npos);
  EXPECT_NE(errorOf([&] { toRgb8(::open3d::geometry::Image()); }).find("empty"), std::string::npos);
  // Open3D does not check that its public members agree; we do.
  ::open3d::geometry::Image truncated = open3dImage(4, 3, 3, 1);
  truncated.data_.resize(30);
  EXPECT_NE(errorOf([&] { Open3dGray g(truncated); }).find("holds 30 bytes, not 36"), std::string::npos);
}

TEST(Open3dImages, GrayOfColorUsesTheBt601WeightsAtTheImagesDepth) {
  ::open3d::geometry::Image rgb = open3dImage(2, 1, 3, 1);
  const std::uint8_t pixels[] = {255, 0, 0, 10, 20, 30};
  for (int i = 0; i < 6; ++i) rgb.data_[i] = pixels[i];
  const Open3dGray gray(rgb);
  ASSERT_FALSE(gray.view().gray8.empty());
  EXPECT_EQ(gray.view().gray8(0, 0), 76);  // 0.299 * 255 = 76.2
  EXPECT_EQ(gray.view().gray8(1, 0), 18);  // 0.299 * 10 + 0.587 * 20 + 0.114 * 30 = 18.1

  ::open3d::geometry::Image rgba16 = open3dImage(1, 1, 4, 2);
  std::uint16_t* p = rgba16.PointerAt<std::uint16_t>(0, 0, 0);
  p[0] = 0;
  p[1] = 65535;
  p[2] = 0;
  p[3] = 1234;  // alpha: ignored
  const Open3dGray gray16(rgba16);
  ASSERT_FALSE(gray16.view().gray16.empty());
  // OpenCV's 16-bit weights have 14 fractional bits: 65535 * 9617 / 2^14 = 38467.4 (0.587 * 65535 = 38469.0).
  EXPECT_EQ(gray16.view().gray16(0, 0), 38467);
}

TEST(Open3dImages, ColorsAreEightBitRgbRoundedFromSixteen) {
  ::open3d::geometry::Image gray16 = open3dImage(4, 1, 1, 2);
  const std::uint16_t values[] = {0, 128, 129, 65535};  // 128/257 rounds down, 129/257 up
  for (int x = 0; x < 4; ++x) *gray16.PointerAt<std::uint16_t>(x, 0) = values[x];
  const Image<Rgb8> color = toRgb8(gray16);
  const std::uint8_t expected[] = {0, 0, 1, 255};
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(color(x, 0).r, expected[x]) << x;
    EXPECT_EQ(color(x, 0).g, expected[x]) << x;
    EXPECT_EQ(color(x, 0).b, expected[x]) << x;
  }
  ::open3d::geometry::Image rgb = open3dImage(1, 1, 3, 1);
  rgb.data_ = {1, 2, 3};
  const Image<Rgb8> same = toRgb8(rgb);
  EXPECT_EQ(same(0, 0).r, 1);
  EXPECT_EQ(same(0, 0).g, 2);
  EXPECT_EQ(same(0, 0).b, 3);
}

TEST(Open3dImages, LidarSgmImagesRoundTripThroughOpen3d) {
  Image<std::uint16_t> depth16(5, 3);
  Image<Rgb8> color(5, 3);
  Image<float> depth(5, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      depth16(x, y) = static_cast<std::uint16_t>(1000 * y + 77 * x + 60000 * (x == 4));
      color(x, y) = Rgb8{static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 250};
      depth(x, y) = 0.25f * static_cast<float>(x + 5 * y);
    }
  }
  const auto o3d16 = toOpen3dImage(depth16.view());
  EXPECT_EQ(o3d16->num_of_channels_, 1);
  EXPECT_EQ(o3d16->bytes_per_channel_, 2);
  const GrayImageView back16 = grayView(*o3d16);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) EXPECT_EQ(back16.gray16(x, y), depth16(x, y)) << x << "," << y;
  }
  const Image<Rgb8> backColor = toRgb8(*toOpen3dImage(color.view()));
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(backColor(x, y).r, x);
      EXPECT_EQ(backColor(x, y).g, y);
      EXPECT_EQ(backColor(x, y).b, 250);
    }
  }
  const auto o3dDepth = toOpen3dImage(depth.view());
  EXPECT_EQ(o3dDepth->bytes_per_channel_, 4);
  EXPECT_EQ(*o3dDepth->PointerAt<float>(3, 2), 3.25f);
  // A view with padded rows: only the pixels are copied.
  Image<std::uint8_t> padded(8, 2);
  for (int i = 0; i < 16; ++i) padded.data()[i] = static_cast<std::uint8_t>(i);
  const auto o3d8 = toOpen3dImage(ImageView<const std::uint8_t>(padded.data(), 5, 2, 8));
  EXPECT_EQ(o3d8->width_, 5);
  EXPECT_EQ(*o3d8->PointerAt<std::uint8_t>(0, 1), 8);
  EXPECT_THROW(toOpen3dImage(ImageView<const std::uint8_t>()), std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
