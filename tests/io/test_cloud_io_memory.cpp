// Clouds from memory: KITTI .bin and PCD bytes give exactly what the file readers give for the
// same bytes, and broken buffers give errors naming the caller's label.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <pcl/io/pcd_io.h>

#include "common/test_data.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using Cloud = pcl::PointCloud<pcl::PointXYZI>;

class CloudMemory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_cloud_mem_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <typename Call>
void expectError(Call call, const std::string& source, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "no exception for '" << source << "'";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'" + source + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

bool sameFloat(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }  // NaN == NaN here

/// Every field of every point bit for bit, the layout, is_dense and the viewpoint.
void expectIdentical(const Cloud& a, const Cloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.is_dense, b.is_dense);
  EXPECT_EQ(a.sensor_origin_, b.sensor_origin_);
  EXPECT_EQ(a.sensor_orientation_.coeffs(), b.sensor_orientation_.coeffs());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(sameFloat(a[i].x, b[i].x) && sameFloat(a[i].y, b[i].y) && sameFloat(a[i].z, b[i].z) &&
                sameFloat(a[i].intensity, b[i].intensity))
        << "point " << i;
  }
}

/// 4 x 3, organized, one NaN point, a viewpoint: every property the readers must carry over.
Cloud organizedCloud() {
  Cloud cloud(4, 3);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto f = static_cast<float>(i);
    cloud[i].x = 0.1f * f - 12.3456789f;
    cloud[i].y = 1.0e-3f * f * f + 3.3333333f;
    cloud[i].z = -7.77f * f + 0.000123f;
    cloud[i].intensity = 0.25f * f + 100.5f;
  }
  cloud[5].x = cloud[5].y = cloud[5].z = std::numeric_limits<float>::quiet_NaN();
  cloud.is_dense = false;
  cloud.sensor_origin_ = Eigen::Vector4f(1.0f, 2.0f, 3.0f, 0.0f);
  cloud.sensor_orientation_ = Eigen::Quaternionf(0.5f, 0.5f, 0.5f, 0.5f);
  return cloud;
}

// ---- KITTI .bin -----------------------------------------------------------------------------

TEST_F(CloudMemory, KittiBinBufferEqualsTheFileReader) {
  const std::vector<float> values = {1.5f, -2.25f, 3.0f, 0.5f, 1e-30f, 7.0f, -0.0f, 0.0f, 40.0f, 0.1f, -1.7f, 0.99f};
  std::ofstream(path("scan.bin"), std::ios::binary)
      .write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * 4));
  const std::string bytes = fileBytes(path("scan.bin"));
  const Cloud fromBuffer = io::readKittiBinFromBuffer(bytes.data(), bytes.size());
  expectIdentical(fromBuffer, io::readKittiBin(path("scan.bin")));
  ASSERT_EQ(fromBuffer.size(), 3u);
  EXPECT_EQ(fromBuffer[1].x, 1e-30f);
  EXPECT_EQ(fromBuffer[2].intensity, 0.99f);
}

TEST_F(CloudMemory, RealKittiScanBufferEqualsTheFileReader) {
  const std::string folder = "kitti_stereo_lidar_calib_nogt";
  if (!test::haveSharedData(folder)) GTEST_SKIP() << "no " << folder;
  fs::path scan;
  for (const auto& entry : fs::recursive_directory_iterator(test::sharedDataRoot() + "/" + folder)) {
    if (entry.path().extension() == ".bin") {
      scan = entry.path();
      break;
    }
  }
  if (scan.empty()) GTEST_SKIP() << "no .bin in " << folder;
  const std::string bytes = fileBytes(scan.string());
  expectIdentical(io::readKittiBinFromBuffer(bytes.data(), bytes.size(), scan.string()),
                  io::readKittiBin(scan.string()));
}

TEST_F(CloudMemory, KittiBinBufferOfWrongSizeNamesTheLabel) {
  const std::vector<unsigned char> bytes(20, 0);
  expectError([&] { io::readKittiBinFromBuffer(bytes.data(), bytes.size(), "scan 3"); }, "scan 3",
              "size 20 bytes is not a multiple of 16");
  expectError([&] { io::readKittiBinFromBuffer(nullptr, 16); }, "<buffer>", "null data pointer");
  const Cloud empty = io::readKittiBinFromBuffer(nullptr, 0);
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.height, 1u);
}

// ---- PCD --------------------------------------------------------------------------------------

enum class Encoding { kAscii, kBinary, kCompressed };

std::string writePcd(const std::string& file, const Cloud& cloud, Encoding encoding) {
  pcl::PCDWriter writer;
  int status = -1;
  switch (encoding) {
    case Encoding::kAscii: status = writer.writeASCII(file, cloud, 9); break;
    case Encoding::kBinary: status = writer.writeBinary(file, cloud); break;
    case Encoding::kCompressed: status = writer.writeBinaryCompressed(file, cloud); break;
  }
  EXPECT_EQ(status, 0) << file;
  return fileBytes(file);
}

const char* name(Encoding encoding) {
  switch (encoding) {
    case Encoding::kAscii: return "ascii";
    case Encoding::kBinary: return "binary";
    case Encoding::kCompressed: return "binary_compressed";
  }
  return "?";
}

TEST_F(CloudMemory, PcdBufferOfEachEncodingEqualsTheFileReader) {
  const Cloud cloud = organizedCloud();
  for (Encoding encoding : {Encoding::kAscii, Encoding::kBinary, Encoding::kCompressed}) {
    SCOPED_TRACE(name(encoding));
    const std::string file = path(std::string(name(encoding)) + ".pcd");
    const std::string bytes = writePcd(file, cloud, encoding);
    const Cloud fromBuffer = io::readPcdFromBuffer(bytes.data(), bytes.size());
    expectIdentical(fromBuffer, io::readPcdOrPly(file));
    // ...and both are the cloud written (ASCII with 9 digits reads floats back exactly).
    expectIdentical(fromBuffer, cloud);
  }
}

TEST_F(CloudMemory, TruncatedPcdBuffersNameTheLabel) {
  const Cloud cloud = organizedCloud();
  for (Encoding encoding : {Encoding::kAscii, Encoding::kBinary, Encoding::kCompressed}) {
    SCOPED_TRACE(name(encoding));
    const std::string bytes = writePcd(path("c.pcd"), cloud, encoding);
    for (std::size_t cut : {std::size_t{1}, std::size_t{20}}) {
      // ASCII cut by one byte loses only the final newline: still complete.
      if (encoding == Encoding::kAscii && cut == 1) continue;
      expectError([&] { io::readPcdFromBuffer(bytes.data(), bytes.size() - cut, "pcd in memory"); }, "pcd in memory",
                  "truncated");
    }
  }
}

TEST_F(CloudMemory, CompressedPcdBufferWithALyingBlockSizeIsRefused) {
  std::string bytes = writePcd(path("c.pcd"), organizedCloud(), Encoding::kCompressed);
  const std::size_t data = bytes.find("DATA binary_compressed\n") + std::strlen("DATA binary_compressed\n");
  const std::uint32_t huge = 1u << 30;
  std::memcpy(&bytes[data], &huge, sizeof huge);  // the block would reach far past the buffer
  expectError([&] { io::readPcdFromBuffer(bytes.data(), bytes.size(), "lzf"); }, "lzf",
              "the compressed block declares 1073741824 bytes");
}

TEST_F(CloudMemory, EmptyAndGarbagePcdBuffersNameTheLabel) {
  const std::string garbage("\x01\x02garbage\xff\xfe not a point cloud\n", 30);
  expectError([&] { io::readPcdFromBuffer(garbage.data(), garbage.size(), "junk"); }, "junk", "not a PCD file");
  expectError([&] { io::readPcdFromBuffer(garbage.data(), 0); }, "<buffer>", "the buffer is empty");
  expectError([&] { io::readPcdFromBuffer(nullptr, 10); }, "<buffer>", "null data pointer");
  const std::string liar =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 5\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5\nDATA binary\n" + std::string(2 * 12, '\0');
  expectError([&] { io::readPcdFromBuffer(liar.data(), liar.size(), "liar"); }, "liar", "truncated");
}

TEST_F(CloudMemory, PcdBufferWithoutZNamesTheField) {
  const std::string text =
      "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2\n";
  expectError([&] { io::readPcdFromBuffer(text.data(), text.size(), "flat"); }, "flat", "no 'z' field");
}

}  // namespace
}  // namespace lidar_sgm
