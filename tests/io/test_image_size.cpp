// io::imageSize: a PNG's size from its header, other formats decoded, and readImage's refusals.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class ImageSize : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_image_size_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// The message of the std::runtime_error that imageSize throws for `file` ("" when none).
  static std::string errorOf(const std::string& file) {
    try {
      io::imageSize(file);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(ImageSize, APngWrittenByOpenCvGivesItsSize) {
  ASSERT_TRUE(cv::imwrite(path("gray.png"), cv::Mat(375, 1242, CV_8UC1, cv::Scalar(9))));
  ASSERT_TRUE(cv::imwrite(path("color16.png"), cv::Mat(7, 3, CV_16UC3, cv::Scalar(1, 2, 3))));
  ASSERT_TRUE(cv::imwrite(path("wide.png"), cv::Mat(1, io::kMaxImageSide, CV_8UC1, cv::Scalar(0))));
  EXPECT_EQ(io::imageSize(path("gray.png")), cv::Size(1242, 375));
  EXPECT_EQ(io::imageSize(path("color16.png")), cv::Size(3, 7));
  EXPECT_EQ(io::imageSize(path("wide.png")), cv::Size(io::kMaxImageSide, 1));
}

TEST_F(ImageSize, APngIsNotDecoded) {
  // The header and then garbage: readImage refuses it, the size is still the header's.
  ASSERT_TRUE(cv::imwrite(path("whole.png"), cv::Mat(40, 60, CV_8UC1, cv::Scalar(5))));
  std::ifstream in(path("whole.png"), std::ios::binary);
  std::string bytes(33, '\0');  // signature and IHDR chunk
  in.read(&bytes[0], static_cast<std::streamsize>(bytes.size()));
  std::ofstream(path("damaged.png"), std::ios::binary) << bytes << std::string(100, 'x');
  EXPECT_THROW(io::readImage(path("damaged.png")), std::runtime_error);
  EXPECT_EQ(io::imageSize(path("damaged.png")), cv::Size(60, 40));
}

TEST_F(ImageSize, OtherFormatsAreDecodedForTheirSize) {
  ASSERT_TRUE(cv::imwrite(path("frame.jpg"), cv::Mat(10, 20, CV_8UC3, cv::Scalar(1, 2, 3))));
  ASSERT_TRUE(cv::imwrite(path("frame.pgm"), cv::Mat(11, 21, CV_8UC1, cv::Scalar(4))));
  EXPECT_EQ(io::imageSize(path("frame.jpg")), cv::Size(20, 10));
  EXPECT_EQ(io::imageSize(path("frame.pgm")), cv::Size(21, 11));
}

TEST_F(ImageSize, APngCutShortBeforeItsSizeIsRefusedNamingIt) {
  ASSERT_TRUE(cv::imwrite(path("cut.png"), cv::Mat(4, 4, CV_8UC1, cv::Scalar(0))));
  fs::resize_file(path("cut.png"), 20);
  EXPECT_EQ(errorOf(path("cut.png")),
            "cannot read image '" + path("cut.png") + "': a PNG cut short: 20 bytes, before its size (bytes 16 to 23)");
}

TEST_F(ImageSize, ReadImagesRefusalsAreItsOwn) {
  EXPECT_EQ(errorOf(path("missing.png")), "cannot read image '" + path("missing.png") + "': no such file");
  std::ofstream(path("notes.png")) << "not an image";
  EXPECT_NE(errorOf(path("notes.png")).find("not a PNG, JPEG or PGM/PPM file"), std::string::npos);
  // A 30000x30000 PNG, refused from its header as readImage refuses it.
  const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                  0, 0, 0x75, 0x30, 0, 0, 0x75, 0x30, 8, 0, 0, 0, 0, 0, 0, 0, 0};
  std::ofstream(path("huge.png"), std::ios::binary).write(reinterpret_cast<const char*>(header), sizeof header);
  const std::string huge = errorOf(path("huge.png"));
  EXPECT_NE(huge.find("30000x30000 pixels is more than the limit of 16384x16384"), std::string::npos) << huge;
  try {
    io::readImage(path("huge.png"));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(huge, e.what());
  }
  // The signature, then a first chunk that is not IHDR.
  std::string noIhdr(reinterpret_cast<const char*>(header), sizeof header);
  noIhdr.replace(12, 4, "IDAT");
  std::ofstream(path("no_ihdr.png"), std::ios::binary) << noIhdr;
  EXPECT_NE(errorOf(path("no_ihdr.png")).find("not a readable image file"), std::string::npos);
}

}  // namespace
}  // namespace lidar_sgm
