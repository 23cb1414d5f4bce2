// The lidar_sgm_densify tool as a user runs it on the bundled synthetic sample (data/sample):
// exit codes, messages, the clouds it writes and the files it leaves behind.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/cloud_preview.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

/// `prefix` runs in the shell first (a ulimit, a trap).
RunResult runTool(const std::string& arguments, const std::string& prefix = "") {
  const std::string command = prefix + std::string(test::kDensifyTool) + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

const std::string kSample = test::kSampleDir;
const std::string kScan = kSample + "/velodyne/000000.bin";
const std::string kCalib = kSample + "/calib/000000.txt";
const std::string kLeft = kSample + "/image_2/000000.png";
const std::string kRight = kSample + "/image_3/000000.png";
constexpr int kWidth = 1242;  // the sample's image size (data/sample/README.md)
constexpr int kHeight = 375;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The "N kept" count of the tool's "Projecting" line; 0 when absent.
std::size_t keptPoints(const std::string& output) {
  std::smatch match;
  const std::regex kept("Projecting \\[done, [0-9.]+ ms : [0-9]+ in: ([0-9]+) kept");
  return std::regex_search(output, match, kept) ? std::stoul(match[1].str()) : 0;
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name) {
  for (const pcl::PCLPointField& field : cloud.fields) {
    if (field.name == name) return true;
  }
  return false;
}

std::string fieldNames(const pcl::PCLPointCloud2& cloud) {
  std::string names;
  for (const pcl::PCLPointField& field : cloud.fields) names += field.name + " ";
  return names;
}

bool isFinitePoint(const pcl::PointXYZ& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

class DensifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_densify_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  /// Files whose name starts with '.' (the tools' temporary files).
  std::vector<std::string> hiddenFiles() const {
    std::vector<std::string> hidden;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (!name.empty() && name[0] == '.') hidden.push_back(name);
    }
    return hidden;
  }
  void writeBytes(const std::string& name, const std::string& bytes) {
    std::ofstream out(p(name), std::ios::binary);
    out << bytes;
    ASSERT_TRUE(out.good());
  }
  /// A small cloud of `n` points in front of (x > 0) or behind (x < 0) the KITTI LiDAR.
  void writeCloud(const std::string& name, bool behind, int n = 50) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    for (int i = 0; i < n; ++i) {
      const float x = behind ? -10.0f - 0.1f * static_cast<float>(i) : 10.0f + 0.1f * static_cast<float>(i);
      cloud.push_back(pcl::PointXYZ(x, 0.05f * static_cast<float>(i % 10) - 0.25f, -0.5f));
    }
    io::writeCloud(p(name), cloud);
  }
  // A failing call must exit non-zero, say `message`, and leave no new file behind.
  void expectFailure(const std::string& arguments, const std::string& message) {
    const std::size_t before = fileCount();
    const RunResult r = runTool(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("Error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << "expected '" << message << "' in:\n" << r.output;
    EXPECT_EQ(fileCount(), before) << "a failed run left a file behind: " << arguments;
    EXPECT_FALSE(fs::exists(p("out.pcd")));
    EXPECT_FALSE(fs::exists(p("out.ply")));
  }

  fs::path dir_;
};

TEST_F(DensifyCli, HelpListsTheOptions) {
  const RunResult r = runTool("-h");
  EXPECT_EQ(r.exitCode, 0);
  for (const char* option : {"-calib", "-left", "-right", "-image_size", "-keep_organized", "-frame", "-max_depth",
                             "-stride", "-no_occlusion_filter", "-disparity", "-depth", "-color", "-alpha", "(default: 80)",
                             "-format binary|compressed|ascii", "(default: binary)", "-scale 1|0.5", "-threads N",
                             "0 = all hardware threads", "-backend", "cpu_ref, cpu", "-preview OUT.png",
                             "-preview_size WxH", "(default: 960x600)", "-preview_height M", "-preview_behind M",
                             "-preview_pitch DEG", "-preview_ground M", "-preview_color image|depth",
                             "-disparity_range lidar|fixed", "-min_confidence", "-confidence OUT.png"}) {
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
  }
}

/// The preview pixel of a rig-camera point, written out from the definition (camera at
/// (0, -height, -behind), pitched down about x; f = W/2 / tan(35 deg)); (-1, -1) when behind it.
cv::Point previewPixel(const pcl::PointXYZRGB& p, int width, int height, double cameraHeight, double behind,
                       double pitchDeg) {
  const double theta = pitchDeg * 3.14159265358979323846 / 180.0;
  const double dy = p.y + cameraHeight;
  const double dz = p.z + behind;
  const double depth = std::sin(theta) * dy + std::cos(theta) * dz;
  if (depth < 0.5) return {-1, -1};
  const double f = 0.5 * width / std::tan(35.0 * 3.14159265358979323846 / 180.0);
  return {static_cast<int>(std::floor(f * p.x / depth + 0.5 * width)),
          static_cast<int>(std::floor(f * (std::cos(theta) * dy - std::sin(theta) * dz) / depth + 0.5 * height))};
}

/// The share of the cloud's points whose preview pixel holds exactly their color.
double shareAtTheirPixel(const pcl::PointCloud<pcl::PointXYZRGB>& cloud, const cv::Mat& preview, double cameraHeight,
                         double behind, double pitchDeg) {
  std::size_t hits = 0;
  for (const pcl::PointXYZRGB& q : cloud) {
    const cv::Point at = previewPixel(q, preview.cols, preview.rows, cameraHeight, behind, pitchDeg);
    if (at.x < 0 || at.y < 0 || at.x >= preview.cols || at.y >= preview.rows) continue;
    hits += preview.at<cv::Vec3b>(at) == cv::Vec3b(q.b, q.g, q.r) ? 1 : 0;
  }
  return static_cast<double>(hits) / static_cast<double>(cloud.size());
}

TEST_F(DensifyCli, PreviewDrawsThePointsWhereTheyProjectInEitherFrame) {
  const std::string common = " -calib " + kCalib + " -left " + kLeft + " -right " + kRight +
                             " -preview_size 481x301 -preview_height 12 -preview_behind 20 -preview_pitch 15";
  const RunResult camera = runTool(kScan + " " + p("camera.pcd") + common + " -frame camera -preview " + p("a.png"));
  ASSERT_EQ(camera.exitCode, 0) << camera.output;
  EXPECT_NE(camera.output.find("Drawing the preview [done"), std::string::npos) << camera.output;
  EXPECT_NE(camera.output.find(", " + p("a.png") + " [done"), std::string::npos) << camera.output;
  const RunResult lidar = runTool(kScan + " " + p("lidar.pcd") + common + " -preview " + p("b.png"));
  ASSERT_EQ(lidar.exitCode, 0) << lidar.output;
  EXPECT_TRUE(hiddenFiles().empty());

  const cv::Mat preview = cv::imread(p("a.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(preview.type(), CV_8UC3);
  EXPECT_EQ(preview.cols, 481);
  EXPECT_EQ(preview.rows, 301);
  EXPECT_GT(fs::file_size(p("a.png")), 1000u);
  // The frame of the cloud file does not change the picture: it is drawn in the camera frame.
  EXPECT_EQ(readText(p("a.png")), readText(p("b.png")));

  // Where the points land: most visible points show their own color at their hand-computed
  // pixel (the rest are hidden behind nearer ones; measured 45 %); one degree of pitch off, far
  // fewer (13 %).
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZRGB>(p("camera.pcd"), cloud), 0);
  ASSERT_GT(cloud.size(), 1000u);
  const double atTheirPixel = shareAtTheirPixel(cloud, preview, 12, 20, 15);
  const double pitchedOff = shareAtTheirPixel(cloud, preview, 12, 20, 16);
  EXPECT_GT(atTheirPixel, 0.2);
  EXPECT_GT(atTheirPixel, 2.0 * pitchedOff) << atTheirPixel << " vs " << pitchedOff;
}

TEST_F(DensifyCli, PreviewWithoutImagesOrAskedForIsDepthColored) {
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -image_size 1242x375 -preview " +
                              p("a.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // With the left image but -preview_color depth: the same picture (LiDAR-only both times).
  const RunResult colored = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft +
                                    " -preview_color depth -preview " + p("b.png"));
  ASSERT_EQ(colored.exitCode, 0) << colored.output;
  EXPECT_EQ(readText(p("a.png")), readText(p("b.png")));
  const cv::Mat preview = cv::imread(p("a.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(preview.type(), CV_8UC3);
  EXPECT_EQ(preview.cols, 960);
  EXPECT_EQ(preview.rows, 600);
  // Turbo colors: some clearly blue (near) and some clearly red (far) pixels.
  std::size_t blue = 0;
  std::size_t red = 0;
  for (int y = 0; y < preview.rows; ++y) {
    for (int x = 0; x < preview.cols; ++x) {
      const cv::Vec3b c = preview.at<cv::Vec3b>(y, x);
      blue += c[0] > 150 && c[2] < 100 ? 1 : 0;
      red += c[2] > 150 && c[0] < 100 ? 1 : 0;
    }
  }
  EXPECT_GT(blue, 100u);
  EXPECT_GT(red, 100u);
}

TEST_F(DensifyCli, FusedRunWritesDenseColoredPcdAndDisparity) {
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " + kRight +
                              " -disparity " + p("d.png") + " -color " + p("c.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* line : {"Loading", "Projecting", "Matching (fused", "Reprojecting", "Saving"}) {
    EXPECT_NE(r.output.find(line), std::string::npos) << line << " in:\n" << r.output;
  }
  EXPECT_EQ(r.output.find("Error"), std::string::npos) << r.output;
  EXPECT_EQ(fileCount(), 3u);
  EXPECT_TRUE(hiddenFiles().empty()) << "temporary file left: " << hiddenFiles().front();

  const std::string text = readText(p("out.pcd"));
  EXPECT_NE(text.find("\nDATA binary\n"), std::string::npos) << text.substr(0, 300);  // the default, the fastest
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZRGB>(p("out.pcd"), cloud), 0);
  const std::size_t kept = keptPoints(r.output);
  ASSERT_GT(kept, 1000u) << r.output;
  EXPECT_GT(cloud.size(), 5 * kept) << "dense " << cloud.size() << " vs " << kept << " projected points";
  EXPECT_EQ(cloud.height, 1u);
  std::size_t nonFinite = 0;  // unorganized output: valid points only
  for (const auto& q : cloud) nonFinite += std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) ? 0 : 1;
  EXPECT_EQ(nonFinite, 0u);
  // Colored from the left image: not one single color.
  bool varied = false;
  for (const auto& q : cloud) varied = varied || q.rgba != cloud.front().rgba;
  EXPECT_TRUE(varied);

  const cv::Mat disparity = cv::imread(p("d.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(disparity.type(), CV_16UC1);
  EXPECT_EQ(disparity.cols, kWidth);
  EXPECT_EQ(disparity.rows, kHeight);
  EXPECT_GT(cv::countNonZero(disparity), kWidth * kHeight / 2);
  const cv::Mat color = cv::imread(p("c.png"), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(color.type(), CV_8UC3);
  EXPECT_EQ(color.cols, kWidth);
}

// Every point carries its pixel's confidence in [0, 1]; -min_confidence keeps exactly the
// points at or above it; -no_confidence gives plain XYZRGB.
TEST_F(DensifyCli, ConfidenceFieldPngAndMinimum) {
  const std::string options = " -calib " + kCalib + " -left " + kLeft + " -right " + kRight;
  RunResult r = runTool(kScan + " " + p("all.pcd") + options +
                        " -min_confidence 0 -confidence " + p("conf.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(p("all.pcd"), blob), 0);
  EXPECT_EQ(fieldNames(blob), "x y z rgb confidence ");
  pcl::PointCloud<PointXYZRGBConfidence> all;
  ASSERT_EQ(pcl::io::loadPCDFile<PointXYZRGBConfidence>(p("all.pcd"), all), 0);
  float lowest = 1.0f, highest = 0.0f;
  for (const auto& q : all) {
    ASSERT_TRUE(q.confidence >= 0.0f && q.confidence <= 1.0f) << q.confidence;
    lowest = std::min(lowest, q.confidence);
    highest = std::max(highest, q.confidence);
  }
  EXPECT_LT(lowest, 0.5f);
  EXPECT_GT(highest, 0.9f);
  const cv::Mat confidence = cv::imread(p("conf.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(confidence.type(), CV_8UC1);
  EXPECT_EQ(confidence.cols, kWidth);
  // Points beyond -max_depth are not written, their pixels keep their confidence.
  EXPECT_GE(static_cast<std::size_t>(cv::countNonZero(confidence)), all.size());

  r = runTool(kScan + " " + p("some.pcd") + options + " -min_confidence 0.9");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  pcl::PointCloud<PointXYZRGBConfidence> some;
  ASSERT_EQ(pcl::io::loadPCDFile<PointXYZRGBConfidence>(p("some.pcd"), some), 0);
  std::size_t expected = 0;
  for (const auto& q : all) expected += q.confidence >= 0.9f - 1e-6f ? 1 : 0;
  EXPECT_EQ(some.size(), expected);
  for (const auto& q : some) ASSERT_GE(q.confidence, 0.9f - 1e-6f);

  r = runTool(kScan + " " + p("plain.pcd") + options + " -no_confidence");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  ASSERT_EQ(pcl::io::loadPCDFile(p("plain.pcd"), blob), 0);
  EXPECT_EQ(fieldNames(blob), "x y z rgb ");
  expectFailure(kScan + " " + p("out.pcd") + options + " -min_confidence 1.5", "-min_confidence");
  expectFailure(kScan + " " + p("out.pcd") + options + " -no_confidence -confidence " +
                    p("c.png"),
                "-no_confidence");
}

TEST_F(DensifyCli, TheSearchRangeComesFromTheLidarUnlessFixed) {
  const std::string line = kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " + kRight;
  const RunResult lidar = runTool(line);
  ASSERT_EQ(lidar.exitCode, 0) << lidar.output;
  std::smatch match;
  const std::string output = lidar.output;
  ASSERT_TRUE(std::regex_search(output, match,
                                std::regex("disparity range: \\[0, ([0-9]+)\\) px from the LiDAR \\(max ([0-9.]+) px\\)")))
      << output;
  const int top = std::stoi(match[1].str());
  const double lidarMax = std::stod(match[2].str());
  EXPECT_EQ(top % 16, 0);
  EXPECT_GE(top, lidarMax + 8.0);  // the rule's least margin
  EXPECT_LT(top, lidarMax + 8.0 + 0.05 * lidarMax + 16.0);
  const RunResult fixed = runTool(line + " -num_disparities 128");
  ASSERT_EQ(fixed.exitCode, 0) << fixed.output;
  EXPECT_NE(fixed.output.find("disparity range: [0, 128) px (fixed)"), std::string::npos) << fixed.output;
}

TEST_F(DensifyCli, LidarOnlyWithLeftImageWritesColoredPly) {
  const RunResult r = runTool(kScan + " " + p("out.ply") + " -calib " + kCalib + " -left " + kLeft);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Matching (lidar-only"), std::string::npos) << r.output;
  EXPECT_EQ(fileCount(), 1u);
  EXPECT_TRUE(readText(p("out.ply")).rfind("ply\nformat binary_little_endian", 0) == 0);
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPLYFile(p("out.ply"), blob), 0);
  EXPECT_TRUE(hasField(blob, "rgb") || hasField(blob, "rgba")) << fieldNames(blob);
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPLYFile<pcl::PointXYZRGB>(p("out.ply"), cloud), 0);
  EXPECT_GT(cloud.size(), 5 * keptPoints(r.output));
  bool varied = false;
  for (const auto& q : cloud) varied = varied || q.rgba != cloud.front().rgba;
  EXPECT_TRUE(varied);
}

TEST_F(DensifyCli, LidarOnlyWithoutImageWritesXyzInLidarFrame) {
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -image_size 1242x375");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Matching (lidar-only"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lidar frame"), std::string::npos) << r.output;
  EXPECT_EQ(fileCount(), 1u);
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(p("out.pcd"), blob), 0);
  EXPECT_EQ(fieldNames(blob), "x y z confidence ");
  EXPECT_FALSE(hasField(blob, "rgb"));
  pcl::PointCloud<pcl::PointXYZ> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZ>(p("out.pcd"), cloud), 0);
  EXPECT_GT(cloud.size(), 5 * keptPoints(r.output));
  std::size_t notForward = 0;
  for (const auto& q : cloud) notForward += isFinitePoint(q) && q.x > 0.0f ? 0 : 1;
  EXPECT_EQ(notForward, 0u) << "LiDAR frame: x forward";
}

TEST_F(DensifyCli, KeepOrganizedInCameraFrameHasOnePointPerPixel) {
  const RunResult r =
      runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -image_size 1242x375 -keep_organized -frame camera");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("camera frame"), std::string::npos) << r.output;
  pcl::PointCloud<pcl::PointXYZ> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZ>(p("out.pcd"), cloud), 0);
  EXPECT_EQ(cloud.width, static_cast<std::uint32_t>(kWidth));
  EXPECT_EQ(cloud.height, static_cast<std::uint32_t>(kHeight));
  std::size_t valid = 0;
  std::size_t notInFront = 0;
  for (const auto& q : cloud) {
    if (!isFinitePoint(q)) continue;
    ++valid;
    notInFront += q.z > 0.0f ? 0 : 1;
  }
  EXPECT_GT(valid, 5 * keptPoints(r.output));
  EXPECT_EQ(notInFront, 0u) << "camera frame: z forward";
}

TEST_F(DensifyCli, DepthPngHoldsEachPointsCameraDepthInKittiFormat) {
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " + kRight +
                              " -keep_organized -frame camera -depth " + p("depth.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const cv::Mat depth = cv::imread(p("depth.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16UC1);
  ASSERT_EQ(depth.cols, kWidth);
  ASSERT_EQ(depth.rows, kHeight);
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZRGB>(p("out.pcd"), cloud), 0);
  ASSERT_EQ(cloud.width, static_cast<std::uint32_t>(kWidth));
  // KITTI depth completion: metres * 256, 0 = none; a pixel has a depth exactly when it has a point.
  std::size_t points = 0;
  std::size_t mismatched = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const pcl::PointXYZRGB& q = cloud.at(x, y);
      const std::uint16_t v = depth.at<std::uint16_t>(y, x);
      if (!std::isfinite(q.z)) {
        mismatched += v != 0 ? 1 : 0;
        continue;
      }
      ++points;
      mismatched += std::abs(v / 256.0 - q.z) <= 0.5 / 256.0 + 1e-6 * q.z ? 0 : 1;
    }
  }
  EXPECT_GT(points, static_cast<std::size_t>(kWidth * kHeight / 2));
  EXPECT_EQ(mismatched, 0u);
}

TEST_F(DensifyCli, KeepOrganizedWithStrideTwoHalvesTheSizeRoundingUp) {
  const RunResult r =
      runTool(kScan + " " + p("out.ply") + " -calib " + kCalib + " -left " + kLeft + " -keep_organized -stride 2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("621x188"), std::string::npos) << r.output;
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPLYFile<pcl::PointXYZRGB>(p("out.ply"), cloud), 0);
  EXPECT_EQ(cloud.width, static_cast<std::uint32_t>((kWidth + 1) / 2));
  EXPECT_EQ(cloud.height, static_cast<std::uint32_t>((kHeight + 1) / 2));
  EXPECT_EQ(cloud.size(), std::size_t{621} * 188);
}

TEST_F(DensifyCli, VoxelKeepsOnePointPerVoxelWithTheAveragedFields) {
  const std::string pair = " -calib " + kCalib + " -left " + kLeft + " -right " + kRight;
  ASSERT_EQ(runTool(kScan + " " + p("full.pcd") + pair).exitCode, 0);
  const RunResult r = runTool(kScan + " " + p("voxel.pcd") + pair + " -voxel 0.2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Down-sampling [done, "), std::string::npos) << r.output;
  pcl::PointCloud<PointXYZRGBConfidence> full;
  pcl::PointCloud<PointXYZRGBConfidence> voxel;
  ASSERT_EQ(pcl::io::loadPCDFile(p("full.pcd"), full), 0);
  ASSERT_EQ(pcl::io::loadPCDFile(p("voxel.pcd"), voxel), 0);
  ASSERT_GT(voxel.size(), 1000u);
  EXPECT_LT(voxel.size() * 4, full.size()) << "a dense frame has many points per 20 cm voxel";
  // One point per voxel: no two output points share a 0.2 m cell (a centroid lies in its cell).
  std::set<std::tuple<long, long, long>> cells;
  for (const auto& q : voxel) {
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    EXPECT_GE(q.confidence, 0.0f);
    EXPECT_LE(q.confidence, 1.0f);
    cells.emplace(static_cast<long>(std::floor(q.x / 0.2f)), static_cast<long>(std::floor(q.y / 0.2f)),
                  static_cast<long>(std::floor(q.z / 0.2f)));
  }
  EXPECT_EQ(cells.size(), voxel.size());
  // The same cloud again: the same bytes.
  ASSERT_EQ(runTool(kScan + " " + p("again.pcd") + pair + " -voxel 0.2").exitCode, 0);
  EXPECT_TRUE(readText(p("again.pcd")) == readText(p("voxel.pcd")));
}

TEST_F(DensifyCli, SixteenBitPairMatchesAtFullDepth) {
  // The sample pair as 16-bit gray, scaled by 257: the same order of intensities, hence the
  // same census and the same disparities as the 8-bit gray the tool makes of the color pair.
  for (const auto& [from, to] : {std::pair<std::string, std::string>{kLeft, "left16.png"}, {kRight, "right16.png"}}) {
    const cv::Mat gray = io::readGrayImage(from);
    cv::Mat wide;
    gray.convertTo(wide, CV_16U, 257.0);
    ASSERT_TRUE(cv::imwrite(p(to), wide));
  }
  // The hidden-LiDAR filter's witness at full scale too: halving the pair averages 2x2 pixels,
  // which rounds 8-bit and 16-bit values apart, so a half-scale witness may differ.
  const std::string witness = " -hidden_lidar_scale 1";
  const RunResult eight = runTool(kScan + " " + p("a.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " +
                                  kRight + " -disparity " + p("a.png") + witness);
  ASSERT_EQ(eight.exitCode, 0) << eight.output;
  const RunResult sixteen = runTool(kScan + " " + p("b.pcd") + " -calib " + kCalib + " -left " + p("left16.png") +
                                    " -right " + p("right16.png") + " -disparity " + p("b.png") + witness);
  ASSERT_EQ(sixteen.exitCode, 0) << sixteen.output;
  const cv::Mat a = cv::imread(p("a.png"), cv::IMREAD_UNCHANGED);
  const cv::Mat b = cv::imread(p("b.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::countNonZero(a != b), 0);
  // Mixed depths are refused.
  expectFailure(kScan + " " + p("c.pcd") + " -calib " + kCalib + " -left " + p("left16.png") + " -right " + kRight,
                "differ in bit depth");
}

TEST_F(DensifyCli, HalfScaleKeepsTheFullResolution) {
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " + kRight +
                              " -scale 0.5 -keep_organized -disparity " + p("d.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("matched at scale 0.5"), std::string::npos) << r.output;
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile<pcl::PointXYZRGB>(p("out.pcd"), cloud), 0);
  EXPECT_EQ(cloud.width, static_cast<std::uint32_t>(kWidth));
  EXPECT_EQ(cloud.height, static_cast<std::uint32_t>(kHeight));
  std::size_t valid = 0;
  for (const auto& q : cloud) valid += std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) ? 1 : 0;
  EXPECT_GT(valid, std::size_t{kWidth} * kHeight / 2);
  const cv::Mat disparity = cv::imread(p("d.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(disparity.type(), CV_16UC1);
  EXPECT_EQ(disparity.cols, kWidth);
  EXPECT_EQ(disparity.rows, kHeight);
  EXPECT_GT(cv::countNonZero(disparity), kWidth * kHeight / 2);
  EXPECT_EQ(fileCount(), 2u);
}

TEST_F(DensifyCli, ThreadCountNeverChangesTheOutput) {
  for (const std::string n : {"1", "2"}) {
    const RunResult r = runTool(kScan + " " + p("t" + n + ".pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " +
                                kRight + " -threads " + n + " -disparity " + p("t" + n + ".png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  EXPECT_GT(readText(p("t1.pcd")).size(), 100000u);
  EXPECT_TRUE(readText(p("t1.pcd")) == readText(p("t2.pcd"))) << "the clouds differ";
  EXPECT_TRUE(readText(p("t1.png")) == readText(p("t2.png"))) << "the disparities differ";
}

TEST_F(DensifyCli, EveryOutputFormatReadsBackTheSamePoints) {
  // Every 4th pixel keeps the ASCII files small; organized, so NaN points are written too.
  const std::string options = " -calib " + kCalib + " -left " + kLeft + " -right " + kRight + " -stride 4 -keep_organized";
  const struct {
    const char* file;
    const char* format;
    const char* marker;
    float relative;  // 0: bit for bit
  } cases[] = {{"b.pcd", "binary", "\nDATA binary\n", 0.0f},
               {"c.pcd", "compressed", "\nDATA binary_compressed\n", 0.0f},
               {"a.pcd", "ascii", "\nDATA ascii\n", 0.0f},
               {"b.ply", "binary", "\nformat binary_little_endian", 0.0f},
               // PCL's ASCII PLY writer keeps 6 significant digits whatever precision it is given.
               {"a.ply", "ascii", "\nformat ascii", 5e-6f}};
  pcl::PointCloud<pcl::PointXYZRGB> reference;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const RunResult r = runTool(kScan + " " + p(c.file) + options + " -format " + c.format);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(std::string("(") + c.format + ")"), std::string::npos) << r.output;
    EXPECT_NE(readText(p(c.file)).find(c.marker), std::string::npos) << readText(p(c.file)).substr(0, 300);
    pcl::PointCloud<pcl::PointXYZRGB> cloud;
    const bool pcd = std::string(c.file).find(".pcd") != std::string::npos;
    ASSERT_EQ(pcd ? pcl::io::loadPCDFile(p(c.file), cloud) : pcl::io::loadPLYFile(p(c.file), cloud), 0);
    if (reference.empty()) {
      reference = cloud;
      ASSERT_EQ(reference.width, static_cast<std::uint32_t>((kWidth + 3) / 4));
      continue;
    }
    ASSERT_EQ(cloud.width, reference.width);
    ASSERT_EQ(cloud.height, reference.height);
    std::size_t different = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const auto& a = cloud[i];
      const auto& e = reference[i];
      const auto near = [&c](float x, float y) { return std::fabs(x - y) <= c.relative * std::fabs(y); };
      const bool same = std::isnan(e.x) ? std::isnan(a.x) && std::isnan(a.y) && std::isnan(a.z)
                                        : near(a.x, e.x) && near(a.y, e.y) && near(a.z, e.z) &&
                                              (a.rgba & 0xFFFFFFu) == (e.rgba & 0xFFFFFFu);  // PLY has no alpha
      different += same ? 0 : 1;
    }
    EXPECT_EQ(different, 0u);
  }
  EXPECT_EQ(fileCount(), 5u);
  EXPECT_TRUE(hiddenFiles().empty());
}

TEST_F(DensifyCli, ASwappedPairIsRefusedUnlessTheCheckIsOff) {
  const std::string swapped = kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kRight + " -right " + kLeft;
  expectFailure(swapped, "the stereo pair looks swapped");
  expectFailure(swapped, "-no_pair_check");
  const RunResult r = runTool(swapped + " -no_pair_check");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(p("out.pcd")));
}

TEST_F(DensifyCli, FailsLoudlyAndLeavesNoOutput) {
  const std::string out = " " + p("out.pcd") + " ";
  const std::string calib = " -calib " + kCalib;
  const std::string pair = " -left " + kLeft + " -right " + kRight;

  expectFailure(kScan + out, "-calib CALIB is required");
  expectFailure(p("missing.bin") + out + calib + pair, "cannot read cloud '" + p("missing.bin") + "': no such file");

  writeBytes("truncated.bin", std::string(100, '\0'));
  expectFailure(p("truncated.bin") + out + calib + pair, "size 100 bytes is not a multiple of 16");
  writeBytes("empty.bin", "");
  expectFailure(p("empty.bin") + out + calib + pair, "'" + p("empty.bin") + "' has no points");

  // A calibration with a malformed number: the message names the file and the key.
  std::string calibText = readText(kCalib);
  const std::size_t p2 = calibText.find("P2: 7.215377");
  ASSERT_NE(p2, std::string::npos);
  calibText.replace(p2, 12, "P2: 7.2x5377");
  writeBytes("bad_calib.txt", calibText);
  expectFailure(kScan + out + " -calib " + p("bad_calib.txt") + pair, p("bad_calib.txt"));
  expectFailure(kScan + out + " -calib " + p("bad_calib.txt") + pair, "key 'P2'");
  expectFailure(kScan + out + " -calib " + p("bad_calib.txt") + pair, "malformed number");
  expectFailure(kScan + out + " -calib " + p("missing_calib.txt") + pair, "missing_calib.txt");

  expectFailure(kScan + out + calib + " -left " + p("missing.png"), "cannot read image '" + p("missing.png") + "'");
  expectFailure(kScan + out + calib + " -left " + kLeft + " -right " + p("missing.png"), "missing.png");
  expectFailure(kScan + out + calib + " -right " + kRight, "-right needs -left");

  ASSERT_TRUE(cv::imwrite(p("small_right.png"), cv::Mat(300, 1000, CV_8UC3, cv::Scalar(10, 20, 30))));
  expectFailure(kScan + out + calib + " -left " + kLeft + " -right " + p("small_right.png"),
                "the left image is 1242x375 but the right image is 1000x300");

  // Images against the size the user or the calibration gives.
  expectFailure(kScan + out + calib + pair + " -image_size 1000x300",
                "the stereo pair is 1242x375 but the calibration is for 1000x300");
  expectFailure(kScan + out + calib + " -left " + kLeft + " -image_size 1000x300",
                "the color image is 1242x375 but the calibration is for 1000x300");
  io::writeCalibrationYaml(p("calib.yaml"), io::readCalibration(kCalib, 1000, 300));
  expectFailure(kScan + out + " -calib " + p("calib.yaml") + pair,
                "the stereo pair is 1242x375 but the calibration is for 1000x300");

  // Outputs: never an input, the right extension, no two outputs on one path.
  writeCloud("front.pcd", /*behind=*/false);
  const std::string frontBefore = readText(p("front.pcd"));
  expectFailure(p("front.pcd") + " " + p("front.pcd") + calib + pair, "refusing to overwrite an input");
  EXPECT_EQ(readText(p("front.pcd")), frontBefore);
  expectFailure(kScan + " " + p("out.txt") + calib + pair, "must be a .pcd or .ply file");
  EXPECT_FALSE(fs::exists(p("out.txt")));
  ASSERT_NO_THROW(fs::copy_file(kLeft, p("left.png")));
  const auto leftSize = fs::file_size(p("left.png"));
  expectFailure(kScan + out + calib + " -left " + p("left.png") + " -disparity " + p("left.png"),
                "refusing to overwrite an input");
  EXPECT_EQ(fs::file_size(p("left.png")), leftSize);
  expectFailure(kScan + out + calib + pair + " -disparity " + p("d.png") + " -color " + p("d.png"),
                "is also another output");
  expectFailure(kScan + out + calib + pair + " -disparity " + p("d.txt"), "must be a .png file");
  expectFailure(kScan + out + calib + pair + " -disparity " + p("d.png") + " -depth " + p("d.png"),
                "is also another output");
  expectFailure(kScan + out + calib + pair + " -depth " + p("d.jpg"), "must be a .png file");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.ppm"), "must be a .png file");
  expectFailure(kScan + out + calib + pair + " -color " + p("v.png") + " -preview " + p("v.png"),
                "is also another output");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -preview_size 8x8",
                "option -preview_*: cloud preview: the picture size 8x8");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -preview_size 640", "option -preview_size");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -preview_pitch 95", "pitch");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -preview_color gray",
                "option -preview_color: 'gray' must be image or depth");
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -preview_height high", "preview_height");
  // Nothing to draw: the empty cloud is named, and no picture is left.
  expectFailure(kScan + out + calib + pair + " -preview " + p("v.png") + " -max_depth 0.01",
                "the dense cloud is empty");

  // Parameters.
  expectFailure(kScan + out + calib + pair + " -alpha 1.5", "alpha = 1.5");
  expectFailure(kScan + out + calib + pair + " -scale 0.7", "invalid parameter scale = 0.7");
  expectFailure(kScan + out + calib + pair + " -scale half", "option -scale: 'half' is not a finite number");
  expectFailure(kScan + out + calib + pair + " -threads -1", "invalid parameter threads = -1");
  expectFailure(kScan + out + calib + pair + " -threads 257", "invalid parameter threads = 257");
  expectFailure(kScan + out + calib + pair + " -scale 0.5 -num_disparities 48",
                "invalid parameter numDisparities = 48: must be a multiple of 32 at scale 0.5");
  expectFailure(kScan + out + calib + pair + " -scale 0.5 -min_disparity 3", "invalid parameter minDisparity = 3");
  expectFailure(kScan + out + calib + pair + " -backend gpu", "option -backend: unknown backend 'gpu'");
  expectFailure(kScan + out + calib + pair + " -disparity_range near", "option -disparity_range: 'near' must be");
  expectFailure(kScan + out + calib + pair + " -format lzf", "option -format: unknown cloud format 'lzf'");
  expectFailure(kScan + " " + p("out.ply") + calib + pair + " -format compressed", "PLY has no compressed form");
  expectFailure(kScan + out + calib + pair + " -paths 3", "paths = 3");
  expectFailure(kScan + out + calib + pair + " -frame up", "option -frame: 'up' must be lidar or camera");
  expectFailure(kScan + out + calib + pair + " -image_size 12x", "option -image_size: '12x' is not WIDTHxHEIGHT");
  expectFailure(kScan + out + calib + pair + " -image_size 0x375", "must be positive");
  expectFailure(kScan + out + calib + pair + " -stride 0", "option -stride: must be >= 1");
  expectFailure(kScan + out + calib + pair + " -max_depth -1", "option -max_depth: must be >= 0");
  expectFailure(kScan + out + calib + pair + " -voxel -0.1", "option -voxel: must be a finite edge >= 0");
  expectFailure(kScan + out + calib + pair + " -voxel 0.1 -keep_organized", "option -voxel: a down-sampled cloud has no");
  expectFailure(kScan + out + calib + pair + " -voxel 0.00001", "option -voxel: 0.000010 m is too small");
  expectFailure(kScan + " " + p("no_such_folder/out.pcd") + calib + pair, "the folder");
  expectFailure(kScan + out + calib + pair + " -color " + p("no_such_folder/c.png"), "does not exist");
  // -image_size may not contradict a calibration that has its own size (YAML, KITTI raw).
  expectFailure(kScan + out + " -calib " + p("calib.yaml") + " -image_size 1242x375",
                "-image_size 1242x375 disagrees with the calibration");
  expectFailure(kScan + out + calib + pair + " -bogus 1", "unknown option -bogus");
  expectFailure(kScan + out + calib + pair + " -alpha", "needs a value");
  expectFailure(kScan + calib + pair, "expected INPUT and OUTPUT, got 1");
  // Limits: each named, before anything large is allocated.
  expectFailure(kScan + out + calib + " -image_size 100000x100000",
                "option -image_size: '100000x100000' is larger than the limit of 16384x16384 pixels");
  expectFailure(kScan + out + calib + pair + " -max_points 1000",
                "31598 points is more than the limit of 1000 points per scan");
  expectFailure(kScan + out + calib + pair + " -max_points -5", "option -max_points: '-5' is not a positive whole");
  ASSERT_TRUE(cv::imwrite(p("one_row.png"), cv::Mat(1, kWidth, CV_8UC3, cv::Scalar(10, 20, 30))));
  expectFailure(kScan + out + calib + " -left " + p("one_row.png"),
                "the image '" + p("one_row.png") + "' is 1242x1: an image needs at least 2x2 pixels");
  fs::create_directories(p("folder.png"));
  expectFailure(kScan + out + calib + pair + " -color " + p("folder.png"), "cannot write '" + p("folder.png") + "': it is a folder");
  fs::remove(p("folder.png"));

  // LiDAR-only on an object-format calibration, no image and no -image_size: no size at all.
  expectFailure(kScan + out + calib, "the calibration has no image size");

  // Every point behind the camera (x < 0 in the KITTI LiDAR frame).
  writeCloud("behind.pcd", /*behind=*/true);
  expectFailure(p("behind.pcd") + out + calib + pair, "behind the camera");
  expectFailure(p("behind.pcd") + " " + p("out.ply") + calib + " -image_size 1242x375", "50 behind the camera");
}

TEST_F(DensifyCli, FailedRunLeavesAnExistingOutputUntouched) {
  writeCloud("behind.pcd", /*behind=*/true);
  writeBytes("out.pcd", "precious, not a cloud\n");
  const RunResult r = runTool(p("behind.pcd") + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft + " -right " +
                              kRight + " -disparity " + p("d.png"));
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("behind the camera"), std::string::npos) << r.output;
  EXPECT_EQ(readText(p("out.pcd")), "precious, not a cloud\n");
  EXPECT_EQ(fileCount(), 2u) << "a failed run left a file behind";

  // A failure after matching: every point is deeper than -max_depth, so there is nothing to write.
  writeBytes("out.ply", "precious too\n");
  const RunResult late =
      runTool(kScan + " " + p("out.ply") + " -calib " + kCalib + " -image_size 1242x375 -max_depth 0.1");
  EXPECT_NE(late.exitCode, 0) << late.output;
  EXPECT_NE(late.output.find("Error: the dense cloud is empty"), std::string::npos) << late.output;
  EXPECT_EQ(readText(p("out.ply")), "precious too\n");
  EXPECT_EQ(fileCount(), 3u) << "a failed run left a file behind";
  EXPECT_TRUE(hiddenFiles().empty());
}

// All-or-nothing: an output that fails after others were written leaves every file as
// it was. The shell's file-size limit makes the second picture fail once the cloud is written
// (SIGXFSZ ignored, so the write fails with EFBIG instead of killing the tool).
TEST_F(DensifyCli, ALateWriteFailureReplacesNoOutputAndLeavesNoTemporary) {
  writeBytes("out.pcd", "precious cloud\n");
  writeBytes("d.png", "precious picture\n");
  const std::string arguments = kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft +
                                " -voxel 2 -disparity " + p("d.png") + " -color " + p("c.png");
  const RunResult r = runTool(arguments, "trap '' XFSZ; ulimit -f 64; ");  // 64 KiB: the cloud fits, not the pictures
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("Error: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Error: cannot write '" + p("d.png") + "': "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no output was replaced"), std::string::npos) << r.output;
  EXPECT_EQ(readText(p("out.pcd")), "precious cloud\n");
  EXPECT_EQ(readText(p("d.png")), "precious picture\n");
  EXPECT_FALSE(fs::exists(p("c.png")));
  EXPECT_TRUE(hiddenFiles().empty());
  // Without the limit the same run replaces both.
  const RunResult ok = runTool(arguments);
  ASSERT_EQ(ok.exitCode, 0) << ok.output;
  EXPECT_NE(readText(p("out.pcd")), "precious cloud\n");
  EXPECT_TRUE(cv::imread(p("d.png"), cv::IMREAD_UNCHANGED).type() == CV_16UC1);
  EXPECT_TRUE(fs::exists(p("c.png")));
  EXPECT_TRUE(hiddenFiles().empty());
}

// SIGTERM while the (slow, ASCII) cloud is being written: the tool dies of the signal, the old
// output is untouched and its temporaries are gone; a temporary left by a killed run (kill -9)
// is removed by the next run.
TEST_F(DensifyCli, SigtermWhileSavingLeavesTheOldOutputAndNoTemporary) {
  writeBytes("out.pcd", "precious cloud\n");
  const std::string arguments = kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft +
                                " -format ascii -disparity " + p("d.png");
  // The shell waits for "Saving" on the tool's output, then sends SIGTERM.
  const std::string script = "(" + std::string(test::kDensifyTool) + " " + arguments + " > " + p("log") +
                             " 2>&1 & pid=$!; for i in $(seq 600); do grep -q Saving " + p("log") +
                             " && break; sleep 0.05; done; kill -TERM $pid; wait $pid; echo status=$?)";
  FILE* pipe = popen(script.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 512> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  pclose(pipe);
  EXPECT_NE(output.find("status=143"), std::string::npos) << output << readText(p("log"));  // 128 + SIGTERM
  EXPECT_EQ(readText(p("out.pcd")), "precious cloud\n");
  EXPECT_FALSE(fs::exists(p("d.png")));
  EXPECT_TRUE(hiddenFiles().empty()) << hiddenFiles().front();

  writeBytes(".out.tmp999999999.pcd", "left by a run killed with -9");  // above any pid: no such process
  const RunResult r = runTool(kScan + " " + p("out.pcd") + " -calib " + kCalib + " -left " + kLeft);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(hiddenFiles().empty());
}

}  // namespace
}  // namespace lidar_sgm
