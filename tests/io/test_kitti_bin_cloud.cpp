// The PCL reader of KITTI .bin (readKittiBin, cloud_io.hpp) is the PCL-free one (readKittiScan,
// kitti_bin.hpp) in a pcl::PointCloud: the same bytes give the same points and the same errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/test_data.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using Cloud = pcl::PointCloud<pcl::PointXYZI>;

class KittiScanCloud : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_kitti_bin_cloud_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream((dir_ / name).string(), std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return (dir_ / name).string();
  }

  fs::path dir_;
};

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// A float's four bytes as a KITTI file stores them (little-endian, whatever the host).
std::string littleEndian(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  std::string bytes;
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((bits >> shift) & 0xffu));
  return bytes;
}

/// Every point bit for bit (NaNs included), and the cloud's layout and denseness.
void expectSamePoints(const Cloud& cloud, const std::vector<io::KittiPoint>& points) {
  ASSERT_EQ(cloud.size(), points.size());
  EXPECT_EQ(cloud.width, points.size());
  EXPECT_EQ(cloud.height, 1u);
  bool finite = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const io::KittiPoint& p = points[i];
    ASSERT_TRUE(sameBits(cloud[i].x, p.x) && sameBits(cloud[i].y, p.y) && sameBits(cloud[i].z, p.z) &&
                sameBits(cloud[i].intensity, p.intensity))
        << i;
    finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  }
  EXPECT_EQ(cloud.is_dense, finite);
}

/// The message of the std::runtime_error `read` throws ("" when it throws none).
std::string errorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST_F(KittiScanCloud, TheSameBytesGiveTheSamePoints) {
  // Random bits: any float, NaN and Inf among them; a NaN intensity alone keeps the cloud dense.
  // 10,000 points: the file is read in blocks of 4,096 records, so two whole blocks and a part.
  std::mt19937 random(11);
  std::string bytes(16 * 10000, '\0');
  for (char& byte : bytes) byte = static_cast<char>(random() & 0xffu);
  const std::string nan = littleEndian(std::numeric_limits<float>::quiet_NaN());
  const std::string scans[] = {bytes, nan + std::string(12, '\0'), std::string(12, '\0') + nan, ""};
  for (const std::string& scan : scans) {
    const std::string file = write("scan.bin", scan);
    const std::vector<io::KittiPoint> points = io::readKittiScan(file);
    expectSamePoints(io::readKittiBin(file), points);
    expectSamePoints(io::readCloud(file), points);
    expectSamePoints(io::readKittiBinFromBuffer(scan.data(), scan.size()), points);
  }
}

TEST_F(KittiScanCloud, EachRefusalIsWordedAlike) {
  const std::string cut = write("cut.bin", std::string(53, '\0'));
  const std::string three = write("three.bin", std::string(48, '\0'));
  fs::create_directories(dir_ / "folder.bin");
  for (const std::string& file : {cut, (dir_ / "none.bin").string(), (dir_ / "folder.bin").string()}) {
    const std::string message = errorOf([&] { io::readKittiScan(file); });
    EXPECT_NE(message, "") << file;
    EXPECT_EQ(errorOf([&] { io::readKittiBin(file); }), message);
    EXPECT_EQ(errorOf([&] { io::readCloud(file); }), message);
  }
  const std::string limit = errorOf([&] { io::readKittiScan(three, 2); });
  EXPECT_NE(limit.find("3 points is more than the limit of 2"), std::string::npos) << limit;
  EXPECT_EQ(errorOf([&] { io::readKittiBin(three, 2); }), limit);
  EXPECT_EQ(errorOf([&] { io::readCloud(three, 2); }), limit);
  const std::vector<char> twenty(20, 0);
  EXPECT_EQ(errorOf([&] { io::readKittiBinFromBuffer(twenty.data(), twenty.size(), "s"); }),
            errorOf([&] { io::readKittiScanFromBuffer(twenty.data(), twenty.size(), "s"); }));
  EXPECT_EQ(errorOf([&] { io::readKittiBinFromBuffer(nullptr, 16); }),
            errorOf([&] { io::readKittiScanFromBuffer(nullptr, 16); }));
}

TEST_F(KittiScanCloud, ARealScanGivesTheSamePoints) {
  if (!test::haveSharedData("kitti_stereo_lidar_calib_nogt")) GTEST_SKIP() << "no shared KITTI data";
  const std::string scan = test::sharedDataRoot() + "/kitti_stereo_lidar_calib_nogt/velodyne/stereo_rcnn_demo.bin";
  expectSamePoints(io::readKittiBin(scan), io::readKittiScan(scan));
}

}  // namespace
}  // namespace lidar_sgm
