#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_io_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

TEST_F(ImageIo, KittiDisparityRoundTripKeepsX16ValuesAndInvalid) {
  Image<std::int16_t> d(3, 2, kInvalidDisparity);
  d(0, 0) = 16 * 10 + 3;  // 10.1875 px
  d(1, 0) = 1;            // 1/16 px
  d(2, 1) = -32;          // negative: KITTI cannot store it -> 0
  io::writeImageAtomically(path("d.png"), io::toKittiDisparity(d.view()));
  const cv::Mat png = cv::imread(path("d.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(png.type(), CV_16UC1);
  EXPECT_EQ(png.at<std::uint16_t>(0, 0), (16 * 10 + 3) * 16);  // disparity * 256
  EXPECT_EQ(png.at<std::uint16_t>(1, 2), 0);
  const Image<std::int16_t> back = io::readKittiDisparity(path("d.png"));
  EXPECT_EQ(back(0, 0), 16 * 10 + 3);
  EXPECT_EQ(back(1, 0), 1);
  EXPECT_EQ(back(0, 1), kInvalidDisparity);
  EXPECT_EQ(back(2, 1), kInvalidDisparity);
  EXPECT_FLOAT_EQ(io::readKittiDisparityFloat(path("d.png"))(0, 0), 10.1875f);
}

TEST_F(ImageIo, DepthIsConvertedWithDisparityEqualsFOverZ) {
  cv::Mat depth(1, 2, CV_16UC1, cv::Scalar(0));
  depth.at<std::uint16_t>(0, 0) = 10 * 256;  // 10 m
  ASSERT_TRUE(cv::imwrite(path("z.png"), depth));
  const Image<std::int16_t> d = io::readKittiDepthAsDisparity(path("z.png"), 384.0);
  EXPECT_EQ(d(0, 0), 614);  // 384/10 = 38.4 px = 614.4 x16
  EXPECT_EQ(d(1, 0), kInvalidDisparity);
  EXPECT_THROW(io::readKittiDepthAsDisparity(path("z.png"), -1.0), std::invalid_argument);
}

TEST_F(ImageIo, MissingMalformedAndWrongFormatFilesAreNamedInTheError) {
  try {
    io::readGrayImage(path("missing.png"));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.png': no such file"), std::string::npos) << e.what();
  }
  std::ofstream(path("junk.png")) << "not a png";
  EXPECT_THROW(io::readGrayImage(path("junk.png")), std::runtime_error);
  ASSERT_TRUE(cv::imwrite(path("rgb.png"), cv::Mat(2, 2, CV_8UC3, cv::Scalar(1, 2, 3))));
  try {
    io::readKittiDisparity(path("rgb.png"));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("16-bit single-channel"), std::string::npos) << e.what();
  }
}

TEST_F(ImageIo, GrayKeepsBitDepthAndConvertsColor) {
  ASSERT_TRUE(cv::imwrite(path("c.png"), cv::Mat(2, 3, CV_8UC3, cv::Scalar(10, 20, 30))));
  ASSERT_TRUE(cv::imwrite(path("g16.png"), cv::Mat(2, 3, CV_16UC1, cv::Scalar(4000))));
  EXPECT_EQ(io::readGrayImage(path("c.png")).type(), CV_8UC1);
  const cv::Mat g16 = io::readGrayImage(path("g16.png"));
  EXPECT_EQ(g16.type(), CV_16UC1);
  const GrayImageView v = io::grayView(g16);
  EXPECT_TRUE(v.gray8.empty());
  EXPECT_EQ(v.gray16(2, 1), 4000);
}

TEST_F(ImageIo, AtomicWriteLeavesOnlyTheFinishedFile) {
  Image<std::int16_t> d(4, 4, 16);
  io::writeImageAtomically(path("out.png"), io::colorizeDisparity(d.view(), 16));
  EXPECT_TRUE(fs::exists(path("out.png")));
  EXPECT_EQ(fileCount(), 1u);
  EXPECT_THROW(io::writeImageAtomically(path("no_such_dir/out.png"), io::toKittiDisparity(d.view())),
               std::runtime_error);
  EXPECT_EQ(fileCount(), 1u);
}

TEST_F(ImageIo, ColorizedInvalidPixelsAreBlack) {
  Image<std::int16_t> d(2, 1, kInvalidDisparity);
  d(1, 0) = 16 * 20;
  const cv::Mat color = io::colorizeDisparity(d.view(), 64);
  EXPECT_EQ(color.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));
  EXPECT_NE(color.at<cv::Vec3b>(0, 1), cv::Vec3b(0, 0, 0));
}

TEST_F(ImageIo, PngLargerThanTheLimitIsRefusedFromItsHeader) {
  // A 30000x30000 PNG took 8.6 GB before failing. Only the header matters here: the
  // size is refused before OpenCV sees the file.
  const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                  0, 0, 0x75, 0x30, 0, 0, 0x75, 0x30, 8, 0, 0, 0, 0, 0, 0, 0, 0};
  std::ofstream(path("huge.png"), std::ios::binary).write(reinterpret_cast<const char*>(header), sizeof header);
  try {
    io::readImage(path("huge.png"));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path("huge.png")), std::string::npos) << message;
    EXPECT_NE(message.find("30000x30000 pixels is more than the limit of 16384x16384"), std::string::npos) << message;
  }
  EXPECT_THROW(io::readKittiDisparity(path("huge.png")), std::runtime_error);
}

TEST_F(ImageIo, PngAtTheLimitSideIsRead) {
  cv::imwrite(path("wide.png"), cv::Mat(1, io::kMaxImageSide, CV_8UC1, cv::Scalar(7)));
  const cv::Mat image = io::readImage(path("wide.png"));
  EXPECT_EQ(image.cols, io::kMaxImageSide);
  EXPECT_EQ(image.at<std::uint8_t>(0, io::kMaxImageSide - 1), 7);
}

}  // namespace
}  // namespace lidar_sgm
