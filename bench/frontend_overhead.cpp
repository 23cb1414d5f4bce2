// The C++ front end's own cost on one frame, for bench/python_overhead.py to compare with: what
// SGMDensification adds around Densifier::run when a frame is densified the way lidar_sgm_densify
// does it (the images converted to gray and set, the cloud converted to a colored PCL cloud).
// Prints the medians of the wall time, of Densifier::run (its own timings) and of the difference.
//
//   build/bench/frontend_overhead [RUNS] [DIR NAME]   (default: 30 runs of data/sample 000000)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "densify/densify_options.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 30;
  const std::string dir = argc > 3 ? argv[2] : LIDAR_SGM_SAMPLE_DIR;
  const std::string name = argc > 3 ? argv[3] : "000000";
  if (runs < 1) {
    std::fprintf(stderr, "usage: %s [RUNS >= 1] [DIR NAME]\n", argv[0]);
    return 2;
  }
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan(
      new pcl::PointCloud<pcl::PointXYZI>(lidar_sgm::io::readCloud(dir + "/velodyne/" + name + ".bin")));
  const cv::Mat left = lidar_sgm::io::readImage(dir + "/image_2/" + name + ".png");
  const cv::Mat right = lidar_sgm::io::readImage(dir + "/image_3/" + name + ".png");
  lidar_sgm::SGMDensification<pcl::PointXYZI, lidar_sgm::PointXYZRGBConfidence> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(lidar_sgm::io::readCalibration(dir + "/calib/" + name + ".txt"));
  pcl::PointCloud<lidar_sgm::PointXYZRGBConfidence> dense;
  std::vector<double> walls;
  std::vector<double> cores;
  std::vector<double> overheads;
  for (int i = 0; i <= runs; ++i) {  // run 0 warms up
    const auto start = std::chrono::steady_clock::now();
    lidar_sgm::apps::setImages(sgm, left, right);  // the tool's gray conversion and color image
    sgm.filter(dense);
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i == 0) continue;
    walls.push_back(wall);
    cores.push_back(sgm.getTimings().total());
    overheads.push_back(wall - sgm.getTimings().total());
  }
  std::printf("%s: %zu points, %d runs\nmedian SGMDensification %.1f ms, Densifier::run %.1f ms, overhead %.2f ms (%.1f %%)\n",
              name.c_str(), dense.size(), runs, median(walls), median(cores), median(overheads),
              100.0 * median(overheads) / median(cores));
  return 0;
}
