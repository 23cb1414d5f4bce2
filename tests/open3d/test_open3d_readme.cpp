// The README's Open3D example, which is also densify.hpp's @code block, compiled and run as
// written on data/sample; the last test checks that the three texts are the same.
// ---- begin README example ----
#include <open3d/io/ImageIO.h>
#include <lidar_sgm/io/calibration_io.hpp>
#include <lidar_sgm/open3d/densify.hpp>

// One KITTI-layout frame, e.g. densify(scan, "data/sample", "000000"); scan: LiDAR frame [m].
std::shared_ptr<open3d::geometry::PointCloud> densify(const open3d::geometry::PointCloud& scan,
                                                      const std::string& dir, const std::string& name) {
  auto left = open3d::io::CreateImageFromFile(dir + "/image_2/" + name + ".png");   // gray/RGB, 8/16 bit
  auto right = open3d::io::CreateImageFromFile(dir + "/image_3/" + name + ".png");  // nullptr -> LiDAR-only
  lidar_sgm::Parameters parameters;              // the tools' defaults
  parameters.alpha = 0.7f;                       // LiDAR weight (Eq. 5)
  return lidar_sgm::densify(scan, lidar_sgm::io::readCalibration(dir + "/calib/" + name + ".txt"),
                            left.get(), right.get(), parameters);  // colors_ in [0, 1] from the left image
}
// ---- end README example ----

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "open3d/open3d_test_helpers.hpp"
#include "common/test_paths.hpp"

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The text between the line that contains `begin` (after it) and the next line containing `end`.
std::string between(const std::string& text, const std::string& begin, const std::string& end) {
  const std::size_t start = text.find(begin);
  if (start == std::string::npos) return "<no '" + begin + "'>";
  const std::size_t first = text.find('\n', start) + 1;
  const std::size_t stop = text.find(end, first);
  if (stop == std::string::npos) return "<no '" + end + "'>";
  return text.substr(first, text.rfind('\n', stop) + 1 - first);
}

/// Doxygen comment lines without their "/// " prefix.
std::string uncomment(const std::string& block) {
  std::istringstream in(block);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find("///");
    line = at == std::string::npos ? line : line.substr(at + 3);
    if (!line.empty() && line[0] == ' ') line.erase(0, 1);
    out += line + "\n";
  }
  return out;
}

}  // namespace

TEST(Open3dReadmeExample, RunsOnTheSample) {
  // The sample scan, as a KITTI .bin (x, y, z, reflectance as float32).
  std::ifstream in(std::string(lidar_sgm::test::kSampleDir) + "/velodyne/000000.bin", std::ios::binary);
  open3d::geometry::PointCloud scan;
  float p[4];
  while (in.read(reinterpret_cast<char*>(p), sizeof(p))) scan.points_.emplace_back(p[0], p[1], p[2]);
  ASSERT_GT(scan.points_.size(), 30000u);  // the sample holds the points in the camera's view (31 598)

  const std::shared_ptr<open3d::geometry::PointCloud> dense = densify(scan, lidar_sgm::test::kSampleDir, "000000");
  // 1242x375 pixels; the scan covers the lower ~2/3 of the image.
  EXPECT_GT(dense->points_.size(), 150000u);
  ASSERT_EQ(dense->colors_.size(), dense->points_.size());
  std::size_t colored = 0;
  for (std::size_t i = 0; i < dense->points_.size(); ++i) {
    ASSERT_TRUE(dense->points_[i].allFinite());
    const Eigen::Vector3d& c = dense->colors_[i];
    ASSERT_TRUE(c.minCoeff() >= 0.0 && c.maxCoeff() <= 1.0);
    colored += c.x() != c.y() || c.y() != c.z() ? 1 : 0;  // the sample's images are in color
  }
  EXPECT_GT(colored, dense->points_.size() / 2);
}

TEST(Open3dReadmeExample, ReadmeHeaderAndThisFileShowTheSameCode) {
  const std::string root = lidar_sgm::test::kSourceDir;
  const std::string here = between(readText(root + "/tests/open3d/test_open3d_readme.cpp"),
                                   "---- begin README example", "---- end README example");
  const std::string readme = readText(root + "/README.md");
  const std::string section = readme.substr(readme.find("## In an Open3D pipeline"));
  EXPECT_EQ(between(section, "```cpp", "```"), here) << "README.md, section 'In an Open3D pipeline (C++)'";
  const std::string header = readText(root + "/include/lidar_sgm/open3d/densify.hpp");
  EXPECT_EQ(uncomment(between(header, "@code", "@endcode")), here) << "densify.hpp's @code block";
}
