// The bench's PGM frame files (bench/pgm_frame.hpp): the format other machines read the real
// frame from, so every byte of it is checked against the PGM format, not only a round trip.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pgm_frame.hpp"

namespace lidar_sgm {
namespace bench {
namespace {
namespace fs = std::filesystem;

class PgmFrame : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_pgm_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void writeBytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  std::string readBytes(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  fs::path dir_;
};

/// The message of the std::runtime_error `fn` throws ("" when it throws none).
template <typename Fn>
std::string errorOf(Fn&& fn) {
  try {
    fn();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

/// An odd-sized frame: a gradient pair and a few LiDAR points, one of them the largest x16 value.
Frame smallFrame() {
  Frame f;
  f.left = Image<std::uint8_t>(7, 5);
  f.right = Image<std::uint8_t>(7, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      f.left(x, y) = static_cast<std::uint8_t>(37 * x + 11 * y);
      f.right(x, y) = static_cast<std::uint8_t>(255 - 29 * x - 7 * y);
    }
  }
  f.lidar = LidarPoints(7, 5, {{0, 0, 1}, {6, 4, 32767}, {3, 2, 16 * 20 + 5}});
  f.source = "a test frame";
  return f;
}

TEST_F(PgmFrame, EightBitFileIsTheP5FormatByteForByte) {
  Image<std::uint8_t> image(3, 2);
  const std::uint8_t pixels[] = {0, 1, 255, 128, 7, 200};
  std::copy(pixels, pixels + 6, image.data());
  writePgm(path("a.pgm"), image.view());
  EXPECT_EQ(readBytes("a.pgm"), std::string("P5\n3 2\n255\n") + std::string(reinterpret_cast<const char*>(pixels), 6));
}

TEST_F(PgmFrame, SixteenBitSamplesAreBigEndian) {
  Image<std::uint16_t> image(2, 1);
  image(0, 0) = 0x1234;
  image(1, 0) = 0xff01;
  writePgm(path("a.pgm"), image.view());
  EXPECT_EQ(readBytes("a.pgm"), std::string("P5\n2 1\n65535\n\x12\x34\xff\x01", 17));
  const Image<std::uint16_t> back = readPgm16(path("a.pgm"));
  EXPECT_EQ(back(0, 0), 0x1234);
  EXPECT_EQ(back(1, 0), 0xff01);
}

TEST_F(PgmFrame, ReadsHeadersWithCommentsAndOtherWhitespace) {
  writeBytes("a.pgm", std::string("P5 # made by hand\n# another comment\n2\t3\r\n100 ") + "\x01\x02\x03\x04\x05\x64");
  const Image<std::uint8_t> image = readPgm8(path("a.pgm"));
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 3);
  EXPECT_EQ(image(0, 0), 1);
  EXPECT_EQ(image(1, 2), 100);
}

TEST_F(PgmFrame, MalformedFilesNameTheFileAndTheProblem) {
  writeBytes("ascii.pgm", "P2\n1 1\n255\n7\n");
  writeBytes("no_height.pgm", "P5\n4 \n");
  writeBytes("zero.pgm", "P5\n0 1\n255\n");
  writeBytes("short.pgm", std::string("P5\n3 2\n255\n") + "abc");
  writeBytes("above_maxval.pgm", std::string("P5\n2 1\n100\n") + "\x05\x65");
  writeBytes("huge_maxval.pgm", "P5\n1 1\n70000\n\x01");
  writeBytes("no_separator.pgm", "P5\n1 1\n255");
  const struct {
    std::string file;
    std::string message;
  } cases[] = {
      {"missing.pgm", "cannot be opened"},
      {"ascii.pgm", "not a binary PGM (it does not start with P5)"},
      {"no_height.pgm", "PGM header has no height"},
      {"zero.pgm", "PGM width is 0"},
      {"short.pgm", "PGM raster is truncated (3 bytes, 3x2 needs 6)"},
      {"above_maxval.pgm", "sample 101 at (1, 0) exceeds maxval 100"},
      {"huge_maxval.pgm", "PGM maxval is larger than 65535"},
      {"no_separator.pgm", "does not end with a whitespace after maxval"},
  };
  for (const auto& c : cases) {
    const std::string message = errorOf([&] { readPgm8(path(c.file)); });
    EXPECT_NE(message.find(path(c.file)), std::string::npos) << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << c.file << ": " << message;
  }
}

TEST_F(PgmFrame, BitDepthMustBeTheOneAsked) {
  writePgm(path("8.pgm"), Image<std::uint8_t>(2, 2, 9).view());
  writePgm(path("16.pgm"), Image<std::uint16_t>(2, 2, 9).view());
  EXPECT_NE(errorOf([&] { readPgm8(path("16.pgm")); }).find("16-bit PGM (maxval 65535) where an 8-bit one is expected"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readPgm16(path("8.pgm")); }).find("8-bit PGM (maxval 255) where a 16-bit one is expected"),
            std::string::npos);
}

TEST_F(PgmFrame, FrameRoundTripKeepsEveryPixelAndPoint) {
  const Frame f = smallFrame();
  writePgmFrame(f, path("frame"));
  const Frame back = readPgmFrame(path("frame"));
  ASSERT_EQ(back.width(), 7);
  ASSERT_EQ(back.height(), 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      EXPECT_EQ(back.left(x, y), f.left(x, y));
      EXPECT_EQ(back.right(x, y), f.right(x, y));
      ASSERT_EQ(back.lidar.count(x, y), f.lidar.count(x, y)) << x << "," << y;
      if (f.lidar.count(x, y) == 1) {
        EXPECT_EQ(*back.lidar.begin(x, y), *f.lidar.begin(x, y));
      }
    }
  }
  EXPECT_EQ(back.lidar.size(), 3u);
  EXPECT_EQ(back.source, "PGM frame folder: a test frame");
  EXPECT_FALSE(back.synthetic);
  // The LiDAR file itself: 0 where there is no point, the x16 disparity big-endian where there is.
  const Image<std::uint16_t> lidar16 = readPgm16(path("frame/lidar16.pgm"));
  EXPECT_EQ(lidar16(1, 0), 0);
  EXPECT_EQ(lidar16(3, 2), 16 * 20 + 5);
}

TEST_F(PgmFrame, FrameWithoutSourceLineStillReads) {
  writePgmFrame(smallFrame(), path("frame"));
  fs::remove(path("frame/source.txt"));
  EXPECT_EQ(readPgmFrame(path("frame")).source, "PGM frame folder");
}

TEST_F(PgmFrame, BadFrameFoldersAreNamed) {
  EXPECT_NE(errorOf([&] { readPgmFrame(path("nowhere")); }).find("no such frame folder"), std::string::npos);

  writePgmFrame(smallFrame(), path("frame"));
  fs::remove(path("frame/lidar16.pgm"));
  EXPECT_NE(errorOf([&] { readPgmFrame(path("frame")); }).find("lidar16.pgm: cannot be opened"), std::string::npos);

  writePgm(path("frame/right.pgm"), Image<std::uint8_t>(6, 5).view());
  EXPECT_NE(errorOf([&] { readPgmFrame(path("frame")); }).find("right.pgm is 6x5 but left.pgm is 7x5"),
            std::string::npos);

  writePgm(path("frame/right.pgm"), Image<std::uint8_t>(7, 5).view());
  Image<std::uint16_t> lidar16(7, 5, 0);
  lidar16(2, 3) = 40000;
  writePgm(path("frame/lidar16.pgm"), lidar16.view());
  EXPECT_NE(errorOf([&] { readPgmFrame(path("frame")); }).find("x16 disparity 40000 at (2, 3) is above 32767"),
            std::string::npos);
  writePgm(path("frame/lidar16.pgm"), Image<std::uint16_t>(7, 4).view());
  EXPECT_NE(errorOf([&] { readPgmFrame(path("frame")); }).find("lidar16.pgm is 7x4 but left.pgm is 7x5"),
            std::string::npos);
}

TEST_F(PgmFrame, ExportRefusesAPixelWithTwoPoints) {
  Frame f = smallFrame();
  f.lidar = LidarPoints(7, 5, {{2, 1, 100}, {2, 1, 120}});
  EXPECT_NE(errorOf([&] { writePgmFrame(f, path("frame")); }).find("pixel (2, 1) has 2 points, a PGM holds one"),
            std::string::npos);
}

}  // namespace
}  // namespace bench
}  // namespace lidar_sgm
