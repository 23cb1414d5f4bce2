// Our PCD and PLY writers against PCL's: the same bytes where PCL's output is the format (ASCII
// and binary PCD, binary PLY, ASCII PLY of values that 6 digits hold), and for the rest (LZF
// compression, ASCII PLY's 9 digits) files that PCL's readers and ours read back bit for bit.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <pcl/common/io.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class CloudWritersMatchPcl : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_writers_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Odd floats (7-9 significant digits), colours (an opaque one packs to a NaN float), confidences,
/// two points with NaN coordinates; `exactInSixDigits`: values that 6 significant digits hold.
pcl::PointCloud<PointXYZRGBConfidence> colouredCloud(std::uint32_t width, std::uint32_t height, bool exactInSixDigits) {
  pcl::PointCloud<PointXYZRGBConfidence> cloud(width, height);
  if (cloud.size() < 5) throw std::invalid_argument("colouredCloud: at least 5 points");
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-80.0f, 80.0f);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    PointXYZRGBConfidence& p = cloud[i];
    if (exactInSixDigits) {
      p.x = 0.5f * static_cast<float>(i) - 3.25f;
      p.y = -0.125f * static_cast<float>(i);
      p.z = 12.0f + static_cast<float>(i % 7);
      p.confidence = 0.25f * static_cast<float>(i % 5);
    } else {
      p.x = coordinate(random);
      p.y = coordinate(random) * 1e-3f;
      p.z = coordinate(random) * 1e3f;
      p.confidence = std::uniform_real_distribution<float>(0.0f, 1.0f)(random);
    }
    p.r = static_cast<std::uint8_t>(37 * i);
    p.g = static_cast<std::uint8_t>(255 - 11 * i);
    p.b = static_cast<std::uint8_t>(i * i);
    p.a = 255;
  }
  cloud[1].r = cloud[1].g = cloud[1].b = 255;  // rgb 0xFFFFFFFF: a NaN as a float
  cloud[3].x = cloud[3].y = cloud[3].z = std::numeric_limits<float>::quiet_NaN();
  cloud[cloud.size() - 2].x = std::numeric_limits<float>::infinity();
  cloud.is_dense = false;
  return cloud;
}

template <typename PointT>
pcl::PCLPointCloud2 blobOf(const pcl::PointCloud<PointT>& cloud) {
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  return blob;
}

const Eigen::Vector4f kOrigin = Eigen::Vector4f::Zero();
const Eigen::Quaternionf kOrientation = Eigen::Quaternionf::Identity();

/// Every record's packed bytes equal (NaN payloads included), fields matched by name.
void expectSameRecords(const pcl::PCLPointCloud2& read, const pcl::PCLPointCloud2& original) {
  ASSERT_EQ(read.width, original.width);
  ASSERT_EQ(read.height, original.height);
  for (const pcl::PCLPointField& field : original.fields) {
    if (field.name == "_") continue;
    const int index = pcl::getFieldIndex(read, field.name);
    ASSERT_GE(index, 0) << field.name;
    const pcl::PCLPointField& other = read.fields[static_cast<std::size_t>(index)];
    ASSERT_EQ(other.datatype, field.datatype) << field.name;
    const std::size_t size = pcl::getFieldSize(field.datatype);
    for (std::size_t i = 0; i < std::size_t{original.width} * original.height; ++i) {
      ASSERT_EQ(std::memcmp(read.data.data() + i * read.point_step + other.offset,
                            original.data.data() + i * original.point_step + field.offset, size),
                0)
          << field.name << " of point " << i;
    }
  }
}

TEST_F(CloudWritersMatchPcl, AsciiPcdIsPclsBytes) {
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{13, 1}, {5, 4}}) {
    const pcl::PCLPointCloud2 blob = blobOf(colouredCloud(width, height, /*exactInSixDigits=*/false));
    io::writeCloud(path("ours.pcd"), blob, io::CloudFormat::Ascii);
    ASSERT_EQ(pcl::PCDWriter().writeASCII(path("pcl.pcd"), blob, kOrigin, kOrientation, 9), 0);
    EXPECT_EQ(bytesOf(path("ours.pcd")), bytesOf(path("pcl.pcd"))) << width << "x" << height;
  }
}

// PCL's blob writer would copy the padding too (as "_" fields): ours packs the fields, and its
// header is the one PCL generates for the packed layout.
TEST_F(CloudWritersMatchPcl, BinaryPcdHasPclsHeaderForThePackedFieldsAndReadsBackExactly) {
  const pcl::PCLPointCloud2 blob = blobOf(colouredCloud(6, 3, false));
  io::writeCloud(path("ours.pcd"), blob, io::CloudFormat::Binary);
  pcl::PCLPointCloud2 packed;
  packed.width = blob.width;
  packed.height = blob.height;
  for (pcl::PCLPointField field : blob.fields) {
    field.offset = packed.point_step;
    packed.point_step += pcl::getFieldSize(field.datatype) * field.count;
    packed.fields.push_back(field);
  }
  const std::string header =
      pcl::PCDWriter().generateHeaderBinary(packed, kOrigin, kOrientation) + "DATA binary\n";
  const std::string ours = bytesOf(path("ours.pcd"));
  EXPECT_EQ(ours.substr(0, header.size()), header);
  EXPECT_EQ(ours.size(), header.size() + std::size_t{packed.point_step} * blob.width * blob.height);
  pcl::PCLPointCloud2 byPcl;
  ASSERT_EQ(pcl::io::loadPCDFile(path("ours.pcd"), byPcl), 0);
  expectSameRecords(byPcl, blob);
}

TEST_F(CloudWritersMatchPcl, CompressedPcdHasPclsHeaderAndReadsBackExactly) {
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{1000, 1}, {40, 30}, {0, 1}}) {
    const bool empty = width == 0;
    const pcl::PCLPointCloud2 blob = blobOf(colouredCloud(empty ? 8 : width, height, /*exactInSixDigits=*/width == 1000));
    pcl::PCLPointCloud2 written = blob;
    if (empty) {
      written.width = 0;
      written.data.clear();
    }
    io::writeCloud(path("ours.pcd"), written, io::CloudFormat::Compressed);
    const std::string ours = bytesOf(path("ours.pcd"));
    const std::string header = pcl::PCDWriter().generateHeaderBinaryCompressed(written, kOrigin, kOrientation) +
                               "DATA binary_compressed\n";
    ASSERT_EQ(ours.substr(0, header.size()), header);
    pcl::PCLPointCloud2 byPcl;
    ASSERT_EQ(pcl::io::loadPCDFile(path("ours.pcd"), byPcl), 0);
    expectSameRecords(byPcl, written);
    expectSameRecords(io::readCloudFields(path("ours.pcd")), written);
    if (width == 1000) {
      EXPECT_LT(ours.size(), header.size() + written.data.size() / 2) << "regular values, not compressed";
    }
  }
}

TEST_F(CloudWritersMatchPcl, BinaryPlyIsPclsBytesUnorganizedAndOrganized) {
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{11, 1}, {4, 5}}) {
    const pcl::PCLPointCloud2 blob = blobOf(colouredCloud(width, height, false));
    io::writeCloud(path("ours.ply"), blob, io::CloudFormat::Binary);
    ASSERT_EQ(pcl::PLYWriter().writeBinary(path("pcl.ply"), blob, kOrigin, kOrientation, /*use_camera=*/false), 0);
    EXPECT_EQ(bytesOf(path("ours.ply")), bytesOf(path("pcl.ply"))) << width << "x" << height;
  }
}

TEST_F(CloudWritersMatchPcl, AsciiPlyIsPclsBytesWhereSixDigitsHoldTheValues) {
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{11, 1}, {4, 5}}) {
    const pcl::PCLPointCloud2 blob = blobOf(colouredCloud(width, height, /*exactInSixDigits=*/true));
    io::writeCloud(path("ours.ply"), blob, io::CloudFormat::Ascii);
    ASSERT_EQ(pcl::PLYWriter().writeASCII(path("pcl.ply"), blob, kOrigin, kOrientation, 9, /*use_camera=*/false), 0);
    EXPECT_EQ(bytesOf(path("ours.ply")), bytesOf(path("pcl.ply"))) << width << "x" << height;
  }
}

// PCL's ASCII PLY keeps 6 digits whatever precision it is given; ours keeps 9, which read back exactly.
TEST_F(CloudWritersMatchPcl, AsciiPlyReadsBackExactly) {
  const pcl::PointCloud<PointXYZRGBConfidence> cloud = colouredCloud(9, 1, /*exactInSixDigits=*/false);
  io::writeCloud(path("ours.ply"), cloud, io::CloudFormat::Ascii);
  pcl::PointCloud<PointXYZRGBConfidence> byPcl;
  ASSERT_EQ(pcl::io::loadPLYFile(path("ours.ply"), byPcl), 0);
  const pcl::PCLPointCloud2 ours = io::readCloudFields(path("ours.ply"));
  pcl::PointCloud<PointXYZRGBConfidence> byUs;
  pcl::fromPCLPointCloud2(ours, byUs);
  // The ASCII vertex list leaves out the points whose x is not finite, as PCL's does.
  std::size_t j = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!std::isfinite(cloud[i].x)) continue;
    for (const auto* read : {&byPcl, &byUs}) {
      ASSERT_LT(j, read->size());
      EXPECT_EQ((*read)[j].x, cloud[i].x) << i;
      EXPECT_EQ((*read)[j].y, cloud[i].y) << i;
      EXPECT_EQ((*read)[j].z, cloud[i].z) << i;
      EXPECT_EQ((*read)[j].confidence, cloud[i].confidence) << i;
      EXPECT_EQ((*read)[j].rgba & 0xFFFFFFu, cloud[i].rgba & 0xFFFFFFu) << i;
    }
    ++j;
  }
  EXPECT_EQ(byUs.size(), j);
}

TEST_F(CloudWritersMatchPcl, OrganizedPlyReadsBackOnItsGrid) {
  const pcl::PointCloud<PointXYZRGBConfidence> cloud = colouredCloud(4, 5, false);
  io::writeCloud(path("ours.ply"), cloud, io::CloudFormat::Binary);
  pcl::PointCloud<PointXYZRGBConfidence> byUs;
  pcl::fromPCLPointCloud2(io::readCloudFields(path("ours.ply")), byUs);
  ASSERT_EQ(byUs.width, 4u);
  ASSERT_EQ(byUs.height, 5u);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!std::isfinite(cloud[i].x)) {
      EXPECT_TRUE(std::isnan(byUs[i].x)) << i;
      continue;
    }
    EXPECT_EQ(byUs[i].x, cloud[i].x) << i;
    EXPECT_EQ(byUs[i].z, cloud[i].z) << i;
    EXPECT_EQ(byUs[i].rgba & 0xFFFFFFu, cloud[i].rgba & 0xFFFFFFu) << i;
  }
}

TEST_F(CloudWritersMatchPcl, AnEmptyCloudIsAValidPly) {
  pcl::PointCloud<pcl::PointXYZ> empty;
  io::writeCloud(path("empty.ply"), empty, io::CloudFormat::Binary);
  EXPECT_EQ(io::readCloudFields(path("empty.ply")).width, 0u);
  EXPECT_EQ(io::readPcdOrPly(path("empty.ply")).size(), 0u);
}

}  // namespace
}  // namespace lidar_sgm
