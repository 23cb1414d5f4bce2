// The README's SGMDensification example, which is also the class's @code block, compiled and
// run as written on data/sample; the last test checks that the three texts are the same.
// ---- begin README example ----
#include <lidar_sgm/io/calibration_io.hpp>
#include <lidar_sgm/io/cloud_io.hpp>
#include <lidar_sgm/io/image_io.hpp>
#include <lidar_sgm/pcl/sgm_densification.hpp>
#include <lidar_sgm/pcl/sgm_densification_opencv.hpp>

// One KITTI-layout frame, e.g. densify("data/sample", "000000").
pcl::PointCloud<pcl::PointXYZRGB> densify(const std::string& dir, const std::string& name) {
  auto scan = lidar_sgm::io::readCloud(dir + "/velodyne/" + name + ".bin").makeShared();  // LiDAR frame
  const cv::Mat left = lidar_sgm::io::readColorImage(dir + "/image_2/" + name + ".png");
  const cv::Mat right = lidar_sgm::io::readColorImage(dir + "/image_3/" + name + ".png");

  lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
  sgm.setInputCloud(scan);                    // setIndices() is honoured
  sgm.setCalibration(lidar_sgm::io::readCalibration(dir + "/calib/" + name + ".txt"));
  lidar_sgm::setStereoPair(sgm, left, right); // cv::Mat; omit -> LiDAR-only SGM
  sgm.setAlpha(0.7f);                         // LiDAR weight (Eq. 5); setConfig() sets everything
  sgm.setNumberOfThreads(0);                  // 0 = all hardware threads; never changes the result
  sgm.setKeepOrganized(false);                // setOutputFrame, setMaxDepth, setStride, setColorImage
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);                          // empty + PCL_ERROR on bad input; getLastError() says why
  return dense;                               // getDisparityImage(), getDepthImage(), getTimings()
}
// ---- end README example ----

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
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

TEST(ReadmeExample, RunsOnTheSample) {
  const pcl::PointCloud<pcl::PointXYZRGB> dense = densify(lidar_sgm::test::kSampleDir, "000000");
  // 1242x375 pixels; the scan covers the lower ~2/3 of the image (about 31 600 points).
  EXPECT_GT(dense.size(), 150000u);
  EXPECT_TRUE(dense.is_dense);
  EXPECT_EQ(dense.height, 1u);
  std::size_t colored = 0;
  for (const auto& p : dense) {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    colored += p.r != p.g || p.g != p.b ? 1 : 0;  // the sample's images are in color
  }
  EXPECT_GT(colored, dense.size() / 2);
}

TEST(ReadmeExample, ReadmeHeaderAndThisFileShowTheSameCode) {
  const std::string root = lidar_sgm::test::kSourceDir;
  const std::string here = between(readText(root + "/tests/pcl/test_readme_example.cpp"),
                                   "---- begin README example", "---- end README example");
  const std::string readme = readText(root + "/README.md");
  const std::string section = readme.substr(readme.find("## In a PCL pipeline"));
  EXPECT_EQ(between(section, "```cpp", "```"), here) << "README.md, section 'In a PCL pipeline'";
  const std::string header = readText(root + "/include/lidar_sgm/pcl/sgm_densification.hpp");
  EXPECT_EQ(uncomment(between(header, "@code", "@endcode")), here) << "sgm_densification.hpp's @code block";
}
