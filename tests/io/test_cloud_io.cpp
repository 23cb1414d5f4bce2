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
#include <pcl/io/ply_io.h>

#include "common/test_data.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

class CloudIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_cloud_io_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  void writeText(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  void writeFloats(const std::string& name, const std::vector<float>& values) const {
    std::ofstream out(path(name), std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()),
              static_cast<std::streamsize>(values.size() * sizeof(float)));
  }
  std::string readText(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  void truncateBy(const std::string& name, std::uintmax_t bytes) const {
    fs::resize_file(path(name), fs::file_size(path(name)) - bytes);
  }

  /// Runs `read`, expects a std::runtime_error naming the file and containing `fragment`.
  template <typename Call>
  void expectError(Call call, const std::string& file, const std::string& fragment) const {
    try {
      call();
      ADD_FAILURE() << "no exception for '" << file << "'";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(file), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }

  fs::path dir_;
};

float relativeTolerance(float expected) { return 1e-6f * std::max(1.0f, std::fabs(expected)); }

template <typename PointT>
pcl::PointCloud<PointT> makeCloud() {
  pcl::PointCloud<PointT> cloud;
  for (int i = 0; i < 7; ++i) {
    PointT p;
    p.x = 0.1f * static_cast<float>(i) - 12.3456789f;
    p.y = 1.0e-3f * static_cast<float>(i * i) + 3.3333333f;
    p.z = -7.77f * static_cast<float>(i) + 0.000123f;
    cloud.push_back(p);
  }
  return cloud;
}

pcl::PointCloud<pcl::PointXYZI> makeXyziCloud() {
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (const pcl::PointXYZ& q : makeCloud<pcl::PointXYZ>()) {
    pcl::PointXYZI p;
    p.x = q.x;
    p.y = q.y;
    p.z = q.z;
    p.intensity = 0.25f * q.x + 100.5f;
    cloud.push_back(p);
  }
  return cloud;
}

pcl::PointCloud<pcl::PointXYZRGB> makeRgbCloud() {
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  std::uint8_t shade = 3;
  for (const pcl::PointXYZ& q : makeCloud<pcl::PointXYZ>()) {
    pcl::PointXYZRGB p(shade, static_cast<std::uint8_t>(255 - shade), static_cast<std::uint8_t>(shade * 2));
    p.x = q.x;
    p.y = q.y;
    p.z = q.z;
    cloud.push_back(p);
    shade = static_cast<std::uint8_t>(shade + 37);
  }
  return cloud;
}

template <typename PointT>
float intensityOf(const PointT&) {
  return 0.0f;
}
template <>
float intensityOf(const pcl::PointXYZI& p) {
  return p.intensity;
}

/// x, y, z (and intensity where the source has one, else 0) equal, or within `relative` of it.
template <typename PointT>
void expectSameXyzi(const pcl::PointCloud<PointT>& expected, const pcl::PointCloud<pcl::PointXYZI>& actual,
                    bool exact) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const PointT& e = expected[i];
    const pcl::PointXYZI& a = actual[i];
    const float wantI = intensityOf(e);
    if (exact) {
      EXPECT_EQ(a.x, e.x) << i;
      EXPECT_EQ(a.y, e.y) << i;
      EXPECT_EQ(a.z, e.z) << i;
      EXPECT_EQ(a.intensity, wantI) << i;
    } else {
      EXPECT_NEAR(a.x, e.x, relativeTolerance(e.x)) << i;
      EXPECT_NEAR(a.y, e.y, relativeTolerance(e.y)) << i;
      EXPECT_NEAR(a.z, e.z, relativeTolerance(e.z)) << i;
      EXPECT_NEAR(a.intensity, wantI, relativeTolerance(wantI)) << i;
    }
  }
}

/// A hand-built cloud: the given fields (one element each, packed), `points` x `values` per field.
pcl::PCLPointCloud2 makeBlob(const std::vector<std::pair<std::string, std::uint8_t>>& fields,
                             const std::vector<std::vector<double>>& points) {
  pcl::PCLPointCloud2 blob;
  std::uint32_t offset = 0;
  std::vector<std::size_t> sizes;
  for (const auto& [name, type] : fields) {
    pcl::PCLPointField f;
    f.name = name;
    f.datatype = type;
    f.count = 1;
    f.offset = offset;
    blob.fields.push_back(f);
    const std::size_t size = pcl::getFieldSize(type);
    sizes.push_back(size);
    offset += static_cast<std::uint32_t>(size);
  }
  blob.point_step = offset;
  blob.width = static_cast<std::uint32_t>(points.size());
  blob.height = 1;
  blob.row_step = blob.point_step * blob.width;
  blob.is_dense = true;
  blob.data.resize(blob.row_step);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t k = 0; k < fields.size(); ++k) {
      std::uint8_t* at = blob.data.data() + i * blob.point_step + blob.fields[k].offset;
      const double v = points[i][k];
      switch (fields[k].second) {
        case pcl::PCLPointField::FLOAT64: std::memcpy(at, &v, 8); break;
        case pcl::PCLPointField::FLOAT32: {
          const auto f = static_cast<float>(v);
          std::memcpy(at, &f, 4);
          break;
        }
        case pcl::PCLPointField::UINT16: {
          const auto u = static_cast<std::uint16_t>(v);
          std::memcpy(at, &u, 2);
          break;
        }
        case pcl::PCLPointField::INT32: {
          const auto n = static_cast<std::int32_t>(v);
          std::memcpy(at, &n, 4);
          break;
        }
        default: ADD_FAILURE() << "makeBlob: unhandled type";
      }
    }
  }
  return blob;
}

// ---- KITTI .bin -----------------------------------------------------------------------------

TEST_F(CloudIo, KittiBinReadsRawFloatsExactly) {
  const std::vector<float> raw = {1.5f,   -2.25f, 0.1f,   0.0f,     //
                                  -80.1f, 3.3e-7f, 1.75f, 0.99f,    //
                                  12.34f, 56.78f, -9.01f, 0.5f};
  writeFloats("scan.bin", raw);
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readKittiBin(path("scan.bin"));
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.width, 3u);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_TRUE(cloud.is_dense);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(cloud[i].x, raw[4 * i + 0]) << i;
    EXPECT_EQ(cloud[i].y, raw[4 * i + 1]) << i;
    EXPECT_EQ(cloud[i].z, raw[4 * i + 2]) << i;
    EXPECT_EQ(cloud[i].intensity, raw[4 * i + 3]) << i;
  }
  // Dispatch by extension, case-insensitive.
  fs::copy_file(path("scan.bin"), path("SCAN.BIN"));
  EXPECT_EQ(io::readCloud(path("SCAN.BIN"))[2].z, -9.01f);
}

TEST_F(CloudIo, KittiBinWithNonFiniteCoordinateIsNotDense) {
  writeFloats("nan.bin", {1.0f, 2.0f, 3.0f, 0.5f, kNaN, 0.0f, 1.0f, 0.5f});
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readKittiBin(path("nan.bin"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_TRUE(std::isnan(cloud[1].x));
  EXPECT_FALSE(cloud.is_dense);
}

TEST_F(CloudIo, TruncatedKittiBinThrowsNamingItsSize) {
  writeFloats("cut.bin", std::vector<float>(12, 1.0f));
  fs::resize_file(path("cut.bin"), 16 * 3 + 5);
  expectError([&] { io::readKittiBin(path("cut.bin")); }, path("cut.bin"), "multiple of 16");
  expectError([&] { io::readCloud(path("cut.bin")); }, path("cut.bin"), "size 53 bytes");
}

TEST_F(CloudIo, EmptyKittiBinGivesEmptyCloud) {
  writeText("empty.bin", "");
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readCloud(path("empty.bin"));
  EXPECT_TRUE(cloud.empty());
  EXPECT_EQ(cloud.width, 0u);
  EXPECT_EQ(cloud.height, 1u);
}

TEST_F(CloudIo, RealKittiScanHasAllItsPoints) {
  if (!test::haveSharedData("kitti_stereo_lidar_calib_nogt")) GTEST_SKIP() << "no shared KITTI data";
  const std::string scan = test::sharedDataRoot() + "/kitti_stereo_lidar_calib_nogt/velodyne/stereo_rcnn_demo.bin";
  ASSERT_EQ(fs::file_size(scan), 1653504u);
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readCloud(scan);
  EXPECT_EQ(cloud.size(), 103344u);
  EXPECT_EQ(cloud.width, 103344u);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_TRUE(cloud.is_dense);
  // A Velodyne HDL-64 sees up to ~120 m; reflectance is in [0, 1].
  for (const pcl::PointXYZI& p : cloud) {
    ASSERT_LT(std::fabs(p.x) + std::fabs(p.y) + std::fabs(p.z), 400.0f);
    ASSERT_GE(p.intensity, 0.0f);
    ASSERT_LE(p.intensity, 1.0f);
  }
}

// ---- PCD in -------------------------------------------------------------------------------

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

template <typename PointT>
void writePcd(const std::string& file, const pcl::PointCloud<PointT>& cloud, PcdEncoding encoding) {
  pcl::PCDWriter writer;
  int status = -1;
  switch (encoding) {
    case PcdEncoding::kAscii: status = writer.writeASCII(file, cloud); break;
    case PcdEncoding::kBinary: status = writer.writeBinary(file, cloud); break;
    case PcdEncoding::kBinaryCompressed: status = writer.writeBinaryCompressed(file, cloud); break;
  }
  ASSERT_EQ(status, 0) << file;
}

template <typename PointT>
void expectPcdRoundTrip(const std::string& file, const pcl::PointCloud<PointT>& cloud) {
  for (PcdEncoding encoding : {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed}) {
    SCOPED_TRACE("encoding " + std::to_string(static_cast<int>(encoding)) + " " + file);
    writePcd(file, cloud, encoding);
    const pcl::PointCloud<pcl::PointXYZI> back = io::readCloud(file);
    EXPECT_EQ(back.width, cloud.width);
    EXPECT_EQ(back.height, cloud.height);
    EXPECT_TRUE(back.is_dense);
    expectSameXyzi(cloud, back, /*exact=*/encoding != PcdEncoding::kAscii);
  }
}

TEST_F(CloudIo, PcdOfEachEncodingAndPointTypeReadsBack) {
  expectPcdRoundTrip(path("xyz.pcd"), makeCloud<pcl::PointXYZ>());
  expectPcdRoundTrip(path("xyzi.pcd"), makeXyziCloud());
  expectPcdRoundTrip(path("xyzrgb.pcd"), makeRgbCloud());
  expectPcdRoundTrip(path("UPPER.PCD"), makeXyziCloud());
}

TEST_F(CloudIo, PcdWithDoubleCoordinatesReadsAsFloat) {
  const std::vector<std::vector<double>> points = {{1.0000001, -2.5, 1e6 + 0.125}, {-0.1, 0.2, 0.3}};
  const pcl::PCLPointCloud2 blob = makeBlob(
      {{"x", pcl::PCLPointField::FLOAT64}, {"y", pcl::PCLPointField::FLOAT64}, {"z", pcl::PCLPointField::FLOAT64}},
      points);
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("double.pcd"), blob), 0);
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readCloud(path("double.pcd"));
  ASSERT_EQ(cloud.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(cloud[i].x, static_cast<float>(points[i][0]));
    EXPECT_EQ(cloud[i].y, static_cast<float>(points[i][1]));
    EXPECT_EQ(cloud[i].z, static_cast<float>(points[i][2]));
    EXPECT_EQ(cloud[i].intensity, 0.0f);
  }
}

TEST_F(CloudIo, PcdWithUint16IntensityIsConverted) {
  const pcl::PCLPointCloud2 blob = makeBlob({{"x", pcl::PCLPointField::FLOAT32},
                                             {"y", pcl::PCLPointField::FLOAT32},
                                             {"z", pcl::PCLPointField::FLOAT32},
                                             {"intensity", pcl::PCLPointField::UINT16}},
                                            {{1, 2, 3, 0}, {4, 5, 6, 65535}, {7, 8, 9, 1234}});
  ASSERT_EQ(pcl::PCDWriter().writeBinaryCompressed(path("u16.pcd"), blob), 0);
  ASSERT_EQ(pcl::PCDWriter().writeASCII(path("u16_ascii.pcd"), blob), 0);
  for (const std::string& file : {path("u16.pcd"), path("u16_ascii.pcd")}) {
    const pcl::PointCloud<pcl::PointXYZI> cloud = io::readCloud(file);
    ASSERT_EQ(cloud.size(), 3u) << file;
    EXPECT_EQ(cloud[0].intensity, 0.0f) << file;
    EXPECT_EQ(cloud[1].intensity, 65535.0f) << file;
    EXPECT_EQ(cloud[2].intensity, 1234.0f) << file;
    EXPECT_EQ(cloud[2].z, 9.0f) << file;
  }
}

TEST_F(CloudIo, ReflectanceFieldIsUsedAsIntensity) {
  const pcl::PCLPointCloud2 blob = makeBlob({{"x", pcl::PCLPointField::FLOAT32},
                                             {"y", pcl::PCLPointField::FLOAT32},
                                             {"z", pcl::PCLPointField::FLOAT32},
                                             {"reflectance", pcl::PCLPointField::FLOAT32}},
                                            {{1, 2, 3, 0.75}});
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("r.pcd"), blob), 0);
  EXPECT_EQ(io::readCloud(path("r.pcd"))[0].intensity, 0.75f);
}

TEST_F(CloudIo, OrganizedPcdKeepsItsLayoutNaNsAndViewpoint) {
  pcl::PointCloud<pcl::PointXYZI> cloud(4, 3);
  for (std::uint32_t v = 0; v < 3; ++v) {
    for (std::uint32_t u = 0; u < 4; ++u) {
      pcl::PointXYZI& p = cloud.at(static_cast<int>(u), static_cast<int>(v));
      p.x = static_cast<float>(u) + 0.5f;
      p.y = static_cast<float>(v) - 0.25f;
      p.z = 10.0f + static_cast<float>(u * v);
      p.intensity = static_cast<float>(u + 10 * v);
    }
  }
  cloud.at(1, 2).x = cloud.at(1, 2).y = cloud.at(1, 2).z = kNaN;
  cloud.at(3, 0).z = kNaN;
  cloud.is_dense = false;
  cloud.sensor_origin_ = Eigen::Vector4f(1.0f, 2.0f, 3.0f, 0.0f);
  for (PcdEncoding encoding : {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed}) {
    SCOPED_TRACE(static_cast<int>(encoding));
    writePcd(path("organized.pcd"), cloud, encoding);
    const pcl::PointCloud<pcl::PointXYZI> back = io::readCloud(path("organized.pcd"));
    EXPECT_EQ(back.width, 4u);
    EXPECT_EQ(back.height, 3u);
    EXPECT_TRUE(back.isOrganized());
    EXPECT_FALSE(back.is_dense);
    EXPECT_TRUE(std::isnan(back.at(1, 2).x));
    EXPECT_TRUE(std::isnan(back.at(3, 0).z));
    EXPECT_EQ(back.at(3, 0).x, 3.5f);
    EXPECT_EQ(back.at(2, 1).z, 12.0f);
    EXPECT_EQ(back.at(2, 1).intensity, 12.0f);
    EXPECT_EQ(back.sensor_origin_.head<3>(), Eigen::Vector3f(1.0f, 2.0f, 3.0f));
  }
}

// ---- PLY in -------------------------------------------------------------------------------

TEST_F(CloudIo, PlyAsciiAndBinaryReadBack) {
  const pcl::PointCloud<pcl::PointXYZ> xyz = makeCloud<pcl::PointXYZ>();
  const pcl::PointCloud<pcl::PointXYZI> xyzi = makeXyziCloud();
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    ASSERT_EQ(pcl::io::savePLYFile(path("xyz.ply"), xyz, binary), 0);
    ASSERT_EQ(pcl::io::savePLYFile(path("xyzi.ply"), xyzi, binary), 0);
    expectSameXyzi(xyz, io::readCloud(path("xyz.ply")), binary);
    expectSameXyzi(xyzi, io::readCloud(path("xyzi.ply")), binary);
  }
}

TEST_F(CloudIo, PlyWithDoubleCoordinatesAndUcharReflectance) {
  writeText("hand.ply",
            "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\nproperty double z\n"
            "property uchar reflectance\nend_header\n1.5 2.5 3.5 200\n-1 0 0.25 7\n");
  const pcl::PointCloud<pcl::PointXYZI> cloud = io::readCloud(path("hand.ply"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud[0].x, 1.5f);
  EXPECT_EQ(cloud[0].z, 3.5f);
  EXPECT_EQ(cloud[0].intensity, 200.0f);
  EXPECT_EQ(cloud[1].z, 0.25f);
  EXPECT_EQ(cloud[1].intensity, 7.0f);
}

// ---- bad input ----------------------------------------------------------------------------

TEST_F(CloudIo, MissingFilesThrowNoSuchFile) {
  for (const char* name : {"none.bin", "none.pcd", "none.ply"}) {
    expectError([&] { io::readCloud(path(name)); }, path(name), "no such file");
  }
  expectError([&] { io::readPcdOrPly(path("none.pcd")); }, path("none.pcd"), "no such file");
  expectError([&] { io::readKittiBin(path("none.bin")); }, path("none.bin"), "no such file");
}

TEST_F(CloudIo, DirectoryIsCalledADirectory) {
  // A folder named like a scan (velodyne/ given for a file, or a .bin folder).
  for (const char* name : {"scan.bin", "scan.pcd", "scan.ply"}) {
    fs::create_directories(path(name));
    expectError([&] { io::readCloud(path(name)); }, path(name), "it is a directory, not a file");
  }
}

TEST_F(CloudIo, EmptyAndGarbageFilesThrow) {
  writeText("empty.pcd", "");
  writeText("empty.ply", "");
  writeText("garbage.pcd", std::string("\x01\x02garbage\xff\xfe not a point cloud\n", 30));
  writeText("garbage.ply", std::string("\x01\x02garbage\xff\xfe not a point cloud\n", 30));
  for (const char* name : {"empty.pcd", "empty.ply", "garbage.pcd", "garbage.ply"}) {
    expectError([&] { io::readCloud(path(name)); }, path(name), "");
  }
  expectError([&] { io::readCloud(path("garbage.pcd")); }, path("garbage.pcd"), "not a PCD file");
}

TEST_F(CloudIo, PcdWithoutZThrowsNamingTheField) {
  pcl::PointCloud<pcl::PointXY> flat;
  flat.push_back(pcl::PointXY(1.0f, 2.0f));
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("flat.pcd"), flat), 0);
  expectError([&] { io::readCloud(path("flat.pcd")); }, path("flat.pcd"), "no 'z' field");
}

TEST_F(CloudIo, IntegerCoordinatesAreRefusedNamingFieldAndType) {
  const pcl::PCLPointCloud2 blob = makeBlob(
      {{"x", pcl::PCLPointField::INT32}, {"y", pcl::PCLPointField::INT32}, {"z", pcl::PCLPointField::INT32}},
      {{1, 2, 3}});
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("int.pcd"), blob), 0);
  expectError([&] { io::readCloud(path("int.pcd")); }, path("int.pcd"), "field 'x' has type int32");
}

TEST_F(CloudIo, TruncatedPcdAndPlyThrow) {
  const pcl::PointCloud<pcl::PointXYZI> cloud = makeXyziCloud();
  writePcd(path("ascii.pcd"), cloud, PcdEncoding::kAscii);
  writePcd(path("binary.pcd"), cloud, PcdEncoding::kBinary);
  writePcd(path("compressed.pcd"), cloud, PcdEncoding::kBinaryCompressed);
  ASSERT_EQ(pcl::io::savePLYFile(path("binary.ply"), cloud, true), 0);
  for (const char* name : {"ascii.pcd", "binary.pcd", "compressed.pcd", "binary.ply"}) {
    truncateBy(name, 20);  // ASCII: cut inside the last line, which PCL alone would accept
    expectError([&] { io::readCloud(path(name)); }, path(name), "truncated");
  }
  // One byte short is enough for binary data.
  writePcd(path("binary.pcd"), cloud, PcdEncoding::kBinary);
  truncateBy("binary.pcd", 1);
  expectError([&] { io::readCloud(path("binary.pcd")); }, path("binary.pcd"), "truncated");
}

TEST_F(CloudIo, PcdHeaderClaimingMorePointsThanTheDataThrows) {
  writeText("liar.pcd",
            "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 5\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5\nDATA binary\n" +
                std::string(2 * 12, '\0'));
  expectError([&] { io::readCloud(path("liar.pcd")); }, path("liar.pcd"), "truncated");
}

TEST_F(CloudIo, UnsupportedExtensionThrowsListingTheAcceptedOnes) {
  writeText("points.xyz", "1 2 3\n");
  expectError([&] { io::readCloud(path("points.xyz")); }, path("points.xyz"), ".bin, .pcd, .ply");
  expectError([&] { io::readPcdOrPly(path("points.xyz")); }, path("points.xyz"), ".pcd or .ply");
}

// ---- writeCloud ---------------------------------------------------------------------------

TEST_F(CloudIo, WrittenPcdIsPackedBinaryByDefaultAndKeepsColors) {
  const pcl::PointCloud<pcl::PointXYZRGB> cloud = makeRgbCloud();
  io::writeCloud(path("rgb.pcd"), cloud);
  EXPECT_EQ(fileCount(), 1u);  // no temporary left
  const std::string text = readText("rgb.pcd");
  EXPECT_NE(text.find("\nFIELDS x y z rgb\n"), std::string::npos) << text.substr(0, 300);
  const std::size_t data = text.find("\nDATA binary\n");
  ASSERT_NE(data, std::string::npos) << text.substr(0, 300);
  // Packed: 16 bytes a point (PCL's PointXYZRGB record has 32, half of it padding).
  EXPECT_EQ(text.size() - (data + std::string("\nDATA binary\n").size()), 16 * cloud.size());
  pcl::PointCloud<pcl::PointXYZRGB> back;
  ASSERT_EQ(pcl::io::loadPCDFile(path("rgb.pcd"), back), 0);
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back[i].x, cloud[i].x);
    EXPECT_EQ(back[i].y, cloud[i].y);
    EXPECT_EQ(back[i].z, cloud[i].z);
    EXPECT_EQ(back[i].rgba, cloud[i].rgba);
  }
  expectSameXyzi(cloud, io::readCloud(path("rgb.pcd")), /*exact=*/true);
}

TEST_F(CloudIo, BinaryPcdIsTheFilePclsTypedWriterMakes) {
  pcl::PointCloud<pcl::PointXYZRGB> organized(5, 3);
  for (std::size_t i = 0; i < organized.size(); ++i) {
    organized[i] = makeRgbCloud()[i % 7];
    organized[i].x += static_cast<float>(i);
  }
  organized[4].x = organized[4].y = organized[4].z = kNaN;
  organized.is_dense = false;
  const pcl::PointCloud<pcl::PointXYZI> xyzi = makeXyziCloud();
  io::writeCloud(path("ours_rgb.pcd"), organized);
  io::writeCloud(path("ours_xyzi.pcd"), xyzi);
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("pcl_rgb.pcd"), organized), 0);
  ASSERT_EQ(pcl::PCDWriter().writeBinary(path("pcl_xyzi.pcd"), xyzi), 0);
  EXPECT_EQ(readText("ours_xyzi.pcd"), readText("pcl_xyzi.pcd"));
  // The same bytes; only rgb's declared type differs: PCL's typed writer says U, a blob made by
  // pcl::toPCLPointCloud2 (which we write) says F, as PCL's blob writers do. Both read back alike.
  std::string ours = readText("ours_rgb.pcd");
  const std::string theirs = readText("pcl_rgb.pcd");
  const std::size_t type = ours.find("\nTYPE F F F F\n");
  ASSERT_NE(type, std::string::npos) << ours.substr(0, 300);
  ours.replace(type, 14, "\nTYPE F F F U\n");
  EXPECT_EQ(ours, theirs);
}

namespace {
/// x, y, z, r, g, b of every point: bit for bit, or within `relative` (NaN stays NaN; the color
/// of a NaN point is not kept by PLY, and PLY has no alpha).
void expectSamePoints(const pcl::PointCloud<pcl::PointXYZRGB>& expected, const pcl::PointCloud<pcl::PointXYZRGB>& actual,
                      float relative = 0.0f) {
  ASSERT_EQ(actual.size(), expected.size());
  EXPECT_EQ(actual.width, expected.width);
  EXPECT_EQ(actual.height, expected.height);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (std::isnan(expected[i].x)) {
      EXPECT_TRUE(std::isnan(actual[i].x) && std::isnan(actual[i].y) && std::isnan(actual[i].z)) << "point " << i;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const float e = expected[i].data[k];
      EXPECT_NEAR(actual[i].data[k], e, relative * std::fabs(e)) << "point " << i << " coordinate " << k;
    }
    EXPECT_EQ(actual[i].rgba & 0xFFFFFFu, expected[i].rgba & 0xFFFFFFu) << "point " << i;
  }
}
}  // namespace

TEST_F(CloudIo, EveryFormatReadsBackTheSamePoints) {
  // Organized, with a NaN point and coordinates that need all 9 significant digits.
  pcl::PointCloud<pcl::PointXYZRGB> cloud(4, 2);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud[i] = makeRgbCloud()[i % 7];
    cloud[i].x = 1.0f / 3.0f + static_cast<float>(i);
    cloud[i].y = -123.456789f * static_cast<float>(i + 1);
  }
  cloud[6].x = cloud[6].y = cloud[6].z = kNaN;
  cloud.is_dense = false;
  const struct {
    const char* file;
    io::CloudFormat format;
    const char* marker;  // what the file's header says
    float relative;      // 0: bit for bit
  } cases[] = {{"b.pcd", io::CloudFormat::Binary, "\nDATA binary\n", 0.0f},
               {"c.pcd", io::CloudFormat::Compressed, "\nDATA binary_compressed\n", 0.0f},
               {"a.pcd", io::CloudFormat::Ascii, "\nDATA ascii\n", 0.0f},
               {"b.ply", io::CloudFormat::Binary, "\nformat binary_little_endian 1.0\n", 0.0f},
               // PCL's ASCII PLY writer keeps 6 significant digits whatever precision it is given.
               {"a.ply", io::CloudFormat::Ascii, "\nformat ascii 1.0\n", 5e-6f}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    io::writeCloud(path(c.file), cloud, c.format);
    EXPECT_NE(readText(c.file).find(c.marker), std::string::npos) << readText(c.file).substr(0, 300);
    pcl::PointCloud<pcl::PointXYZRGB> back;
    const std::string extension = fs::path(c.file).extension().string();
    ASSERT_EQ(extension == ".pcd" ? pcl::io::loadPCDFile(path(c.file), back) : pcl::io::loadPLYFile(path(c.file), back), 0);
    expectSamePoints(cloud, back, c.relative);
    // Our reader too (it drops the color).
    const pcl::PointCloud<pcl::PointXYZI> xyzi = io::readCloud(path(c.file));
    ASSERT_EQ(xyzi.size(), cloud.size());
    EXPECT_NEAR(xyzi[7].y, cloud[7].y, c.relative * std::fabs(cloud[7].y));
    EXPECT_TRUE(std::isnan(xyzi[6].x));
  }
  EXPECT_EQ(fileCount(), 5u);  // no temporary left
}

TEST_F(CloudIo, CloudFormatNames) {
  for (io::CloudFormat format : {io::CloudFormat::Binary, io::CloudFormat::Compressed, io::CloudFormat::Ascii}) {
    EXPECT_EQ(io::cloudFormatFromString(io::toString(format)), format);
  }
  EXPECT_EQ(io::toString(io::CloudFormat::Compressed), "compressed");
  try {
    io::cloudFormatFromString("lzf");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lzf': must be binary, compressed or ascii"), std::string::npos) << e.what();
  }
}

TEST_F(CloudIo, CompressedPlyIsRefusedBeforeAnythingIsWritten) {
  EXPECT_THROW(io::checkCloudOutput(path("x.ply"), io::CloudFormat::Compressed), std::invalid_argument);
  EXPECT_THROW(io::checkCloudOutput(path("x.xyz"), io::CloudFormat::Binary), std::invalid_argument);
  EXPECT_NO_THROW(io::checkCloudOutput(path("x.PLY"), io::CloudFormat::Ascii));
  EXPECT_NO_THROW(io::checkCloudOutput(path("x.pcd"), io::CloudFormat::Compressed));
  expectError([&] { io::writeCloud(path("x.ply"), makeXyziCloud(), io::CloudFormat::Compressed); }, path("x.ply"),
              "PLY has no compressed form");
  EXPECT_EQ(fileCount(), 0u);
}

TEST_F(CloudIo, WrittenPlyIsBinaryAndReadsBack) {
  const pcl::PointCloud<pcl::PointXYZI> cloud = makeXyziCloud();
  io::writeCloud(path("out.PLY"), cloud);
  EXPECT_EQ(fileCount(), 1u);
  EXPECT_EQ(readText("out.PLY").rfind("ply\nformat binary_", 0), 0u);
  pcl::PointCloud<pcl::PointXYZI> back;
  ASSERT_EQ(pcl::io::loadPLYFile(path("out.PLY"), back), 0);
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back[i].x, cloud[i].x);
    EXPECT_EQ(back[i].z, cloud[i].z);
    EXPECT_EQ(back[i].intensity, cloud[i].intensity);
  }
  expectSameXyzi(cloud, io::readCloud(path("out.PLY")), /*exact=*/true);
}

TEST_F(CloudIo, WrittenOrganizedCloudsKeepTheirLayout) {
  pcl::PointCloud<pcl::PointXYZ> cloud(4, 3);
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud[i] = pcl::PointXYZ(static_cast<float>(i), 1.0f, 2.0f);
  cloud[5].x = cloud[5].y = cloud[5].z = kNaN;
  cloud.is_dense = false;
  for (const char* name : {"org.pcd", "org.ply"}) {
    SCOPED_TRACE(name);
    io::writeCloud(path(name), cloud);
    const pcl::PointCloud<pcl::PointXYZI> back = io::readCloud(path(name));
    EXPECT_EQ(back.width, 4u);
    EXPECT_EQ(back.height, 3u);
    ASSERT_EQ(back.size(), 12u);
    EXPECT_EQ(back[11].x, 11.0f);
    EXPECT_TRUE(std::isnan(back[5].x));
    EXPECT_FALSE(back.is_dense);
  }
}

TEST_F(CloudIo, WriteIntoMissingDirectoryThrowsAndLeavesNothing) {
  for (const char* name : {"missing_subdir/x.pcd", "missing_subdir/x.ply"}) {
    for (io::CloudFormat format : {io::CloudFormat::Binary, io::CloudFormat::Ascii}) {
      expectError([&] { io::writeCloud(path(name), makeXyziCloud(), format); }, path(name), "cannot write");
      EXPECT_FALSE(fs::exists(path(name)));
    }
  }
  expectError([&] { io::writeCloud(path("missing_subdir/x.pcd"), makeXyziCloud(), io::CloudFormat::Compressed); },
              path("missing_subdir/x.pcd"), "cannot write");
  EXPECT_EQ(fileCount(), 0u);
}

TEST_F(CloudIo, WriteWithUnsupportedExtensionThrowsAndLeavesNothing) {
  expectError([&] { io::writeCloud(path("x.xyz"), makeXyziCloud()); }, path("x.xyz"), ".pcd, .ply");
  expectError([&] { io::writeCloud(path("noext"), makeXyziCloud()); }, path("noext"), "unsupported extension");
  EXPECT_EQ(fileCount(), 0u);
}

TEST_F(CloudIo, EmptyCloudWritesInEveryFormat) {
  const pcl::PointCloud<pcl::PointXYZI> empty;
  for (io::CloudFormat format : {io::CloudFormat::Binary, io::CloudFormat::Compressed, io::CloudFormat::Ascii}) {
    SCOPED_TRACE(io::toString(format));
    for (const char* name : {"empty.pcd", "empty.ply"}) {
      if (format == io::CloudFormat::Compressed && std::string(name) == "empty.ply") continue;  // refused: no such PLY
      io::writeCloud(path(name), empty, format);
      EXPECT_TRUE(io::readCloud(path(name)).empty()) << name;
    }
  }
  EXPECT_EQ(fileCount(), 2u);
}

TEST_F(CloudIo, ExistingFileIsReplacedOnlyOnSuccess) {
  pcl::PointCloud<pcl::PointXYZI> first = makeXyziCloud();
  io::writeCloud(path("x.pcd"), first);
  pcl::PointCloud<pcl::PointXYZI> second = makeXyziCloud();
  second.resize(2);
  second[0].x = 42.0f;
  io::writeCloud(path("x.pcd"), second);
  EXPECT_EQ(io::readCloud(path("x.pcd")).size(), 2u);
  EXPECT_EQ(io::readCloud(path("x.pcd"))[0].x, 42.0f);
  const std::string before = readText("x.pcd");

  // An inconsistent cloud is refused before anything is written.
  pcl::PCLPointCloud2 broken;
  pcl::toPCLPointCloud2(first, broken);
  broken.data.resize(broken.data.size() - 1);
  expectError([&] { io::writeCloud(path("x.pcd"), broken); }, path("x.pcd"), "inconsistent");
  EXPECT_EQ(readText("x.pcd"), before);
  // So is a typed cloud whose width x height is not its size (the points are written in place).
  pcl::PointCloud<pcl::PointXYZI> wrongSize = makeXyziCloud();
  wrongSize.width = 100;
  for (io::CloudFormat format : {io::CloudFormat::Binary, io::CloudFormat::Compressed}) {
    expectError([&] { io::writeCloud(path("x.pcd"), wrongSize, format); }, path("x.pcd"), "inconsistent");
  }
  EXPECT_EQ(readText("x.pcd"), before);

  // The temporary's name (dir/.stem.tmpPID.ext) is taken: the next free one is used, and what
  // holds the name is left alone (a write cut short is test_cloud_writer_faults.cpp's).
  const fs::path blocker = dir_ / (".x.tmp" + std::to_string(::getpid()) + ".pcd");
  fs::create_directories(blocker / "inside");
  io::writeCloud(path("x.pcd"), first);
  EXPECT_EQ(io::readCloud(path("x.pcd")).size(), first.size());
  EXPECT_TRUE(fs::is_directory(blocker / "inside"));
  fs::remove_all(blocker);

  // The rename fails: the destination is a non-empty folder; the temporary is removed.
  fs::create_directories(dir_ / "taken.pcd" / "inside");
  expectError([&] { io::writeCloud(path("taken.pcd"), first); }, path("taken.pcd"), "cannot write");
  EXPECT_TRUE(fs::is_directory(dir_ / "taken.pcd"));
  EXPECT_EQ(fileCount(), 2u);  // x.pcd and the folder taken.pcd, no temporary
}

}  // namespace
}  // namespace lidar_sgm
