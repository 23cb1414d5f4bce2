// io's own image codecs (libpng, libjpeg, PGM/PPM) against OpenCV's imgcodecs as the oracle: the
// same pixels read from every kind of file a rig or a tool writes, the same PNG bytes written.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "common/test_paths.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class ImageCodecs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_codecs_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

std::vector<std::uint8_t> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Odd sizes on purpose; seeded, with runs of equal pixels so that the encoder's RLE matters.
cv::Mat randomImage(int type, unsigned seed) {
  cv::Mat image(23, 37, type);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  image(cv::Rect(3, 5, 20, 9)).setTo(cv::Scalar::all(7));
  return image;
}

void expectSamePixels(const cv::Mat& ours, const cv::Mat& opencv, const std::string& what) {
  ASSERT_FALSE(opencv.empty()) << what;
  ASSERT_EQ(ours.type(), opencv.type()) << what;
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  EXPECT_EQ(cv::norm(ours, opencv, cv::NORM_INF), 0.0) << what;
}

const int kTypes[] = {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3, CV_16UC4};

TEST_F(ImageCodecs, PngReadsAsOpenCvReadsEveryTypeAndLevel) {
  unsigned seed = 1;
  for (int type : kTypes) {
    for (int level : {-1, 0, 9}) {
      const std::string file = path("in.png");
      std::vector<int> params;
      if (level >= 0) params = {cv::IMWRITE_PNG_COMPRESSION, level};
      ASSERT_TRUE(cv::imwrite(file, randomImage(type, seed++), params));
      expectSamePixels(io::readImage(file), cv::imread(file, cv::IMREAD_UNCHANGED),
                       "type " + std::to_string(type) + ", level " + std::to_string(level));
    }
  }
}

TEST_F(ImageCodecs, PngWritesOpenCvsBytes) {
  unsigned seed = 100;
  for (int type : kTypes) {
    for (int level : {-1, 0, 1, 6, 9}) {
      const cv::Mat image = randomImage(type, seed++);
      std::vector<int> params;
      if (level >= 0) params = {cv::IMWRITE_PNG_COMPRESSION, level};
      std::vector<std::uint8_t> expected;
      ASSERT_TRUE(cv::imencode(".png", image, expected, params));
      const std::string file = path("out.png");
      if (level >= 0) {
        io::writeImageAtomically(file, image, params);
      } else {
        io::writeImageAtomically(file, image);
      }
      EXPECT_EQ(fileBytes(file), expected) << "type " << type << ", level " << level;
    }
  }
}

TEST_F(ImageCodecs, RealFramesReadAsOpenCvReadsThem) {
  const fs::path sample = test::kSampleDir;
  for (const char* name : {"image_2/000000.png", "disp_gt/000000.png", "depth_gt/000000.png", "mask/000000.png"}) {
    const std::string file = (sample / name).string();
    expectSamePixels(io::readImage(file), cv::imread(file, cv::IMREAD_UNCHANGED), name);
  }
  const fs::path kitti = fs::path(test::kSharedDataDir) / "kitti2015_lidar";
  if (!fs::is_directory(kitti)) GTEST_SKIP() << kitti << " is absent";
  for (const char* name : {"image_2/000007_10.png", "disp_occ_0/000007_10.png", "obj_map/000007_10.png"}) {
    const std::string file = (kitti / name).string();
    expectSamePixels(io::readImage(file), cv::imread(file, cv::IMREAD_UNCHANGED), name);
  }
}

TEST_F(ImageCodecs, JpegReadsAsOpenCvReadsGrayAndColor) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const std::string file = path("in.jpg");
    ASSERT_TRUE(cv::imwrite(file, randomImage(type, 7), {cv::IMWRITE_JPEG_QUALITY, 90}));
    expectSamePixels(io::readImage(file), cv::imread(file, cv::IMREAD_UNCHANGED), "type " + std::to_string(type));
  }
}

TEST_F(ImageCodecs, PgmAndPpmReadAsOpenCvReadsThem) {
  for (int type : {CV_8UC1, CV_8UC3, CV_16UC1, CV_16UC3}) {
    for (int binary : {1, 0}) {
      const std::string file = path(CV_MAT_CN(type) == 1 ? "in.pgm" : "in.ppm");
      ASSERT_TRUE(cv::imwrite(file, randomImage(type, 11), {cv::IMWRITE_PXM_BINARY, binary}));
      expectSamePixels(io::readImage(file), cv::imread(file, cv::IMREAD_UNCHANGED),
                       "type " + std::to_string(type) + (binary != 0 ? ", binary" : ", ascii"));
    }
  }
  // What other writers do: a comment, a maxval below 255 (ASCII samples are scaled to 0-255),
  // a sample above maxval (clamped), a 16-bit maxval.
  const std::string ascii = path("hand.pgm");
  std::ofstream(ascii) << "P2\n# a comment\n3 2\n100\n0 50 100\n7 200 99\n";
  expectSamePixels(io::readImage(ascii), cv::imread(ascii, cv::IMREAD_UNCHANGED), "P2, maxval 100");
  const std::string wide = path("wide.ppm");
  std::ofstream(wide) << "P3 2 1 1000\n1 2 3 999 1000 4\n";
  expectSamePixels(io::readImage(wide), cv::imread(wide, cv::IMREAD_UNCHANGED), "P3, maxval 1000");
  const std::string binary = path("low.pgm");
  std::ofstream(binary, std::ios::binary) << "P5 2 2 15\n" << std::string("\x01\x0f\x10\xff", 4);
  expectSamePixels(io::readImage(binary), cv::imread(binary, cv::IMREAD_UNCHANGED), "P5, maxval 15");
}

TEST_F(ImageCodecs, DamagedFilesAreRefusedNamingTheFile) {
  const cv::Mat image = randomImage(CV_8UC3, 3);
  std::vector<std::uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", image, png));
  const std::string cut = path("cut.png");
  std::ofstream(cut, std::ios::binary).write(reinterpret_cast<const char*>(png.data()),
                                             static_cast<std::streamsize>(png.size() / 2));
  try {
    io::readImage(cut);
    FAIL() << "a PNG cut in half was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read image '" + cut + "': not a readable image file"),
              std::string::npos)
        << e.what();
  }
  std::vector<std::uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", image, jpeg));
  const std::string jpegCut = path("cut.jpg");
  std::ofstream(jpegCut, std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()), 40);
  EXPECT_THROW(io::readImage(jpegCut), std::runtime_error);
  const std::string pgmCut = path("cut.pgm");
  std::ofstream(pgmCut, std::ios::binary) << "P5 4 4 255\n" << std::string(5, 'x');
  EXPECT_THROW(io::readImage(pgmCut), std::runtime_error);
}

TEST_F(ImageCodecs, WritesPngOnlyAndRefusesWhatPngCannotHold) {
  const cv::Mat image = randomImage(CV_8UC3, 5);
  EXPECT_THROW(io::writeImageAtomically(path("out.jpg"), image), std::runtime_error);
  EXPECT_THROW(io::writeImageAtomically(path("out.png"), cv::Mat(4, 4, CV_32FC1, cv::Scalar(1))), std::runtime_error);
  EXPECT_THROW(io::writeImageAtomically(path("out.png"), cv::Mat(4, 4, CV_8UC2, cv::Scalar(1))), std::runtime_error);
  EXPECT_THROW(io::writeImageAtomically(path("out.png"), image, {cv::IMWRITE_PNG_COMPRESSION, 10}),
               std::invalid_argument);
  EXPECT_THROW(io::writeImageAtomically(path("out.png"), image, {cv::IMWRITE_JPEG_QUALITY, 90}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path("out.png")));
}

}  // namespace
}  // namespace lidar_sgm
