// Our PCD and PLY readers against PCL's on files PCL's writers made: the same points (bit for
// bit, NaNs where PCL has NaNs), the same layout and viewpoint. Plus the bounded LZF decoder.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "io/lzf_decoder.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using Cloud = pcl::PointCloud<pcl::PointXYZI>;

class StrictReaders : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_strict_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

/// An organized 5 x 3 XYZI cloud with odd values and two NaN points.
Cloud organizedCloud() {
  Cloud cloud(5, 3);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float t = static_cast<float>(i);
    cloud[i].x = 0.1f * t - 12.3456789f;
    cloud[i].y = 1.0e-3f * t * t + 3.3333333f;
    cloud[i].z = -7.77f * t + 0.000123f;
    cloud[i].intensity = 0.25f * t + 0.5f;
  }
  cloud[4].x = cloud[4].y = cloud[4].z = std::numeric_limits<float>::quiet_NaN();
  cloud[11].x = cloud[11].y = cloud[11].z = std::numeric_limits<float>::quiet_NaN();
  cloud.is_dense = false;
  cloud.sensor_origin_ = Eigen::Vector4f(1.5f, -2.0f, 0.25f, 0.0f);
  cloud.sensor_orientation_ = Eigen::Quaternionf(0.5f, 0.5f, -0.5f, 0.5f);
  return cloud;
}

bool sameFloat(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

/// x, y, z equal bit for bit (NaN to NaN), and intensity where `withIntensity`.
void expectSamePoints(const Cloud& ours, const Cloud& pcls, bool withIntensity) {
  ASSERT_EQ(ours.width, pcls.width);
  ASSERT_EQ(ours.height, pcls.height);
  ASSERT_EQ(ours.size(), pcls.size());
  for (std::size_t i = 0; i < ours.size(); ++i) {
    EXPECT_TRUE(sameFloat(ours[i].x, pcls[i].x)) << i << ": " << ours[i].x << " vs " << pcls[i].x;
    EXPECT_TRUE(sameFloat(ours[i].y, pcls[i].y)) << i;
    EXPECT_TRUE(sameFloat(ours[i].z, pcls[i].z)) << i;
    if (withIntensity && !std::isnan(pcls[i].x)) {
      EXPECT_TRUE(sameFloat(ours[i].intensity, pcls[i].intensity)) << i;
    }
  }
  // is_dense is ours: from the points (PCL's PLY reader copies whatever the writer claimed).
  bool finite = true;
  for (const pcl::PointXYZI& p : ours) finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  EXPECT_EQ(ours.is_dense, finite);
}

TEST_F(StrictReaders, PcdOfEveryEncodingAndPointTypeReadsAsPclReadsIt) {
  const Cloud xyzi = organizedCloud();
  pcl::PointCloud<pcl::PointXYZRGB> rgb;
  pcl::copyPointCloud(xyzi, rgb);
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::copyPointCloud(xyzi, xyz);
  pcl::PCDWriter writer;
  for (int encoding = 0; encoding < 3; ++encoding) {
    SCOPED_TRACE(encoding);
    const auto write = [&](const std::string& file, const auto& cloud) {
      const int status = encoding == 0   ? writer.writeASCII(file, cloud, 9)
                         : encoding == 1 ? writer.writeBinary(file, cloud)
                                         : writer.writeBinaryCompressed(file, cloud);
      ASSERT_EQ(status, 0);
    };
    write(path("xyzi.pcd"), xyzi);
    write(path("rgb.pcd"), rgb);
    write(path("xyz.pcd"), xyz);
    for (const char* name : {"xyzi.pcd", "rgb.pcd", "xyz.pcd"}) {
      SCOPED_TRACE(name);
      Cloud pcls;
      ASSERT_EQ(pcl::io::loadPCDFile(path(name), pcls), 0);
      const Cloud ours = io::readCloud(path(name));
      expectSamePoints(ours, pcls, std::string(name) == "xyzi.pcd");
      EXPECT_EQ(ours.sensor_origin_, pcls.sensor_origin_);
      EXPECT_EQ(ours.sensor_orientation_.coeffs(), pcls.sensor_orientation_.coeffs());
    }
  }
}

TEST_F(StrictReaders, PlyOfEveryWriterReadsAsPclReadsIt) {
  const Cloud cloud = organizedCloud();
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  pcl::PLYWriter writer;
  const Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  const Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  for (bool binary : {false, true}) {
    for (bool camera : {false, true}) {
      SCOPED_TRACE(std::string(binary ? "binary" : "ascii") + (camera ? " camera" : " range_grid"));
      const std::string file = path("cloud.ply");
      const int status = binary ? writer.writeBinary(file, blob, origin, orientation, camera)
                                : writer.writeASCII(file, blob, origin, orientation, 9, camera);
      ASSERT_EQ(status, 0);
      Cloud pcls;
      ASSERT_EQ(pcl::io::loadPLYFile(file, pcls), 0);
      const Cloud ours = io::readCloud(file);
      expectSamePoints(ours, pcls, true);
    }
  }
}

TEST_F(StrictReaders, BigEndianPlyReadsAsLittleEndian) {
  const auto write = [&](const std::string& file, const std::string& format, bool swap) {
    std::ofstream out(path(file), std::ios::binary);
    out << "ply\nformat " << format << " 1.0\nelement vertex 2\nproperty float x\nproperty double y\n"
        << "property float z\nproperty ushort intensity\nend_header\n";
    for (int i = 0; i < 2; ++i) {
      const float x = 1.25f + static_cast<float>(i);
      const double y = -3.5e-3 * (i + 1);
      const float z = 1e20f;
      const std::uint16_t intensity = static_cast<std::uint16_t>(4097 + i);
      for (const auto& [bytes, size] : {std::pair<const void*, std::size_t>{&x, 4}, {&y, 8}, {&z, 4}, {&intensity, 2}}) {
        std::vector<char> b(static_cast<const char*>(bytes), static_cast<const char*>(bytes) + size);
        if (swap) std::reverse(b.begin(), b.end());
        out.write(b.data(), static_cast<std::streamsize>(b.size()));
      }
    }
  };
  write("little.ply", "binary_little_endian", false);
  write("big.ply", "binary_big_endian", true);
  const Cloud little = io::readCloud(path("little.ply"));
  const Cloud big = io::readCloud(path("big.ply"));
  ASSERT_EQ(little.size(), 2u);
  expectSamePoints(big, little, true);
  EXPECT_EQ(little[1].x, 2.25f);
  EXPECT_EQ(little[1].y, static_cast<float>(-7e-3));
  EXPECT_EQ(little[1].intensity, 4098.0f);
}

TEST_F(StrictReaders, DoubleBeyondFloatRangeBecomesInfinity) {
  std::ofstream(path("far.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 8 8 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\n"
                                 << "POINTS 1\nDATA ascii\n1e300 -1e300 1e39\n";
  const Cloud cloud = io::readCloud(path("far.pcd"));
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud[0].x, std::numeric_limits<float>::infinity());
  EXPECT_EQ(cloud[0].y, -std::numeric_limits<float>::infinity());
  EXPECT_EQ(cloud[0].z, std::numeric_limits<float>::infinity());
  EXPECT_FALSE(cloud.is_dense);
}

TEST_F(StrictReaders, IntegerValuesOutOfTheirTypesRangeAreRefused) {
  std::ofstream(path("u8.pcd")) << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 1\nTYPE F F F U\nWIDTH 1\n"
                                << "HEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 256\n";
  EXPECT_THROW(io::readCloud(path("u8.pcd")), std::runtime_error);
  std::ofstream(path("neg.pcd")) << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 2\nTYPE F F F U\nWIDTH 1\n"
                                 << "HEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 -1\n";
  EXPECT_THROW(io::readCloud(path("neg.pcd")), std::runtime_error);
}

TEST_F(StrictReaders, AsciiPcdWithExtraPointsOrValuesIsRefusedNamingTheLine) {
  std::ofstream(path("extra.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\n"
                                   << "POINTS 1\nDATA ascii\n1 2 3\n4 5 6\n";
  try {
    io::readCloud(path("extra.pcd"));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 10: more points than the header's POINTS 1"), std::string::npos)
        << e.what();
  }
}

TEST_F(StrictReaders, PcdHeaderKeysAreCheckedOnceEach) {
  const std::string rest = "SIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
  std::ofstream(path("twice.pcd")) << "FIELDS x y z\nWIDTH 1\n" << rest;
  EXPECT_THROW(io::readCloud(path("twice.pcd")), std::runtime_error);
  std::ofstream(path("unknown.pcd")) << "FIELDS x y z\nCOLOR 1\n" << rest;
  EXPECT_THROW(io::readCloud(path("unknown.pcd")), std::runtime_error);
  std::ofstream(path("dupfield.pcd")) << "FIELDS x y x\n" << rest;
  EXPECT_THROW(io::readCloud(path("dupfield.pcd")), std::runtime_error);
  std::ofstream(path("nodata.pcd")) << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n";
  EXPECT_THROW(io::readCloud(path("nodata.pcd")), std::runtime_error);
  std::ofstream(path("ok.pcd")) << "FIELDS x y z\n" << rest;
  EXPECT_EQ(io::readCloud(path("ok.pcd")).size(), 1u);
}

TEST(Lzf, DecodesLiteralsAndOverlappingReferences) {
  // "abc" as a literal run, then a 6-byte reference 3 back: "abcabcabc".
  const std::uint8_t in[] = {2, 'a', 'b', 'c', (4 << 5) | 0, 2};
  std::uint8_t out[9] = {};
  ASSERT_TRUE(io::detail::lzfDecode(in, sizeof in, out, sizeof out));
  EXPECT_EQ(std::string(reinterpret_cast<char*>(out), 9), "abcabcabc");
}

TEST(Lzf, RefusesEveryOutOfBoundsStep) {
  std::uint8_t out[16] = {};
  const std::uint8_t literalPastInput[] = {5, 'a', 'b'};
  EXPECT_FALSE(io::detail::lzfDecode(literalPastInput, sizeof literalPastInput, out, sizeof out));
  const std::uint8_t literalPastOutput[] = {3, 'a', 'b', 'c', 'd'};
  EXPECT_FALSE(io::detail::lzfDecode(literalPastOutput, sizeof literalPastOutput, out, 3));
  const std::uint8_t referenceBeforeStart[] = {0, 'a', (1 << 5) | 0, 1};
  EXPECT_FALSE(io::detail::lzfDecode(referenceBeforeStart, sizeof referenceBeforeStart, out, sizeof out));
  const std::uint8_t referencePastOutput[] = {0, 'a', (7 << 5) | 0, 200, 0};
  EXPECT_FALSE(io::detail::lzfDecode(referencePastOutput, sizeof referencePastOutput, out, sizeof out));
  const std::uint8_t cutReference[] = {0, 'a', (1 << 5)};
  EXPECT_FALSE(io::detail::lzfDecode(cutReference, sizeof cutReference, out, sizeof out));
  const std::uint8_t shortOutput[] = {0, 'a'};
  EXPECT_FALSE(io::detail::lzfDecode(shortOutput, sizeof shortOutput, out, 2));
}

}  // namespace
}  // namespace lidar_sgm
