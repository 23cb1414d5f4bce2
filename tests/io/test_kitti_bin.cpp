// The PCL-free KITTI .bin reader (kitti_bin.hpp): the points as stored, and every refusal named.
// This suite builds without PCL; the same points as the PCL reader: test_kitti_bin_cloud.cpp.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/io/kitti_bin.hpp"

// The header's promise: no PCL (every PCL header includes pcl_config.h, which defines this).
#ifdef PCL_MAJOR_VERSION
#error "lidar_sgm/io/kitti_bin.hpp must not include PCL"
#endif

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class KittiScan : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_kitti_bin_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// The floats as a KITTI file stores them: little-endian, whatever the host.
  static std::string littleEndianBytes(const std::vector<float>& values) {
    std::string bytes;
    for (const float value : values) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((bits >> shift) & 0xffu));
    }
    return bytes;
  }
  std::string writeFloats(const std::string& name, const std::vector<float>& values) const {
    const std::string bytes = littleEndianBytes(values);
    std::ofstream(path(name), std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path(name);
  }

  fs::path dir_;
};

/// Runs `call`, expects a std::runtime_error "cannot read cloud '<source>': ..." containing `fragment`.
template <typename Call>
void expectError(Call call, const std::string& source, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "no exception for '" << source << "'";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("cannot read cloud '" + source + "': ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectPoints(const std::vector<io::KittiPoint>& points, const std::vector<float>& raw) {
  ASSERT_EQ(points.size() * 4, raw.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_TRUE(sameBits(points[i].x, raw[4 * i + 0])) << i;
    EXPECT_TRUE(sameBits(points[i].y, raw[4 * i + 1])) << i;
    EXPECT_TRUE(sameBits(points[i].z, raw[4 * i + 2])) << i;
    EXPECT_TRUE(sameBits(points[i].intensity, raw[4 * i + 3])) << i;
  }
}

TEST_F(KittiScan, ReadsEachRecordsFloatsExactlyInFileOrder) {
  const std::vector<float> raw = {1.5f,   -2.25f,  0.1f,   0.0f,   //
                                  -80.1f, 3.3e-7f, 1.75f,  0.99f,  //
                                  12.34f, 56.78f,  -9.01f, 0.5f};
  expectPoints(io::readKittiScan(writeFloats("scan.bin", raw)), raw);
}

TEST_F(KittiScan, NonFiniteValuesAreKeptAsStored) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> raw = {1.0f, 2.0f, 3.0f, 0.5f, nan, 0.0f, -inf, nan, 4.0f, inf, 5.0f, 0.25f};
  const std::vector<io::KittiPoint> points = io::readKittiScan(writeFloats("nan.bin", raw));
  expectPoints(points, raw);
  EXPECT_TRUE(std::isnan(points[1].x));
  EXPECT_TRUE(std::isinf(points[2].y));
}

TEST_F(KittiScan, AnEmptyFileGivesNoPoints) {
  EXPECT_TRUE(io::readKittiScan(writeFloats("empty.bin", {})).empty());
}

TEST_F(KittiScan, ASizeThatIsNotWholeRecordsIsRefusedNamingIt) {
  writeFloats("cut.bin", std::vector<float>(12, 1.0f));
  fs::resize_file(path("cut.bin"), 16 * 3 + 5);
  expectError([&] { io::readKittiScan(path("cut.bin")); }, path("cut.bin"),
              "size 53 bytes is not a multiple of 16 (x, y, z, reflectance float32): truncated?");
}

TEST_F(KittiScan, MorePointsThanTheLimitAreRefusedBeforeReading) {
  const std::string scan = writeFloats("three.bin", std::vector<float>(12, 1.0f));
  EXPECT_EQ(io::readKittiScan(scan, 3).size(), 3u);
  expectError([&] { io::readKittiScan(scan, 2); }, scan, "3 points is more than the limit of 2 points per scan");
  // The default limit, on a sparse file: refused from its size, its 800 MB never read.
  fs::resize_file(scan, (io::kMaxCloudPoints + 1) * 16);
  expectError([&] { io::readKittiScan(scan); }, scan,
              std::to_string(io::kMaxCloudPoints + 1) + " points is more than the limit of " +
                  std::to_string(io::kMaxCloudPoints) + " points per scan");
}

TEST_F(KittiScan, AMissingFileOrAFolderIsNamed) {
  expectError([&] { io::readKittiScan(path("none.bin")); }, path("none.bin"), "no such file");
  fs::create_directories(path("folder.bin"));
  expectError([&] { io::readKittiScan(path("folder.bin")); }, path("folder.bin"), "it is a directory, not a file");
}

TEST_F(KittiScan, ABufferGivesWhatTheFileGives) {
  const std::vector<float> raw = {1.5f, -2.25f, 3.0f, 0.5f, 1e-30f, 7.0f, -0.0f, 0.0f};
  const std::string bytes = littleEndianBytes(raw);
  const std::vector<io::KittiPoint> fromBuffer = io::readKittiScanFromBuffer(bytes.data(), bytes.size());
  expectPoints(fromBuffer, raw);
  expectPoints(io::readKittiScan(writeFloats("scan.bin", raw)), raw);
}

TEST_F(KittiScan, ABrokenBufferIsNamedByItsLabel) {
  const std::vector<unsigned char> bytes(20, 0);
  expectError([&] { io::readKittiScanFromBuffer(bytes.data(), bytes.size(), "scan 3"); }, "scan 3",
              "size 20 bytes is not a multiple of 16");
  expectError([&] { io::readKittiScanFromBuffer(nullptr, 16); }, "<buffer>", "null data pointer for 16 bytes");
  EXPECT_TRUE(io::readKittiScanFromBuffer(nullptr, 0).empty());
}

}  // namespace
}  // namespace lidar_sgm
