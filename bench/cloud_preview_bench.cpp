// cloud_preview_bench: how long io::renderCloudPreview takes for a real dense cloud. Reads a
// camera-frame XYZRGB PCD (lidar_sgm_densify ... -frame camera), renders it `-runs` times after
// two warm-up renders, and prints the median wall-clock and thread CPU time of one render.
//   cloud_preview_bench CLOUD.pcd [-runs N]
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/arguments.hpp"
#include "common/tool_main.hpp"
#include "thread_cpu.hpp"
#include "lidar_sgm/io/cloud_preview.hpp"

namespace {

using lidar_sgm::bench::medianOf;
using lidar_sgm::bench::threadCpuMs;

int run(int argc, char** argv) {
  const lidar_sgm::apps::Arguments args(argc, argv, {"runs"}, {});
  if (args.positionals().size() != 1) throw std::invalid_argument("expected CLOUD.pcd (camera frame, XYZRGB)");
  const int runs = args.integer("runs", 21);
  if (runs < 1) throw std::invalid_argument("option -runs: must be >= 1");
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  if (pcl::io::loadPCDFile(args.positionals()[0], cloud) != 0) {
    throw std::runtime_error("cannot read '" + args.positionals()[0] + "'");
  }
  std::vector<Eigen::Vector3f> points;
  std::vector<lidar_sgm::Rgb8> colors;
  for (const auto& p : cloud) {
    points.emplace_back(p.x, p.y, p.z);
    colors.push_back({p.r, p.g, p.b});
  }
  const lidar_sgm::io::CloudPreviewOptions options;
  std::vector<double> wall;
  std::vector<double> cpu;
  for (int i = 0; i < runs + 2; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = threadCpuMs();
    const cv::Mat picture = lidar_sgm::io::renderCloudPreview(points, colors, options);
    const double cpuMs = threadCpuMs() - cpuStart;
    const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i < 2) continue;  // warm-up
    wall.push_back(wallMs);
    cpu.push_back(cpuMs);
  }
  std::printf("cloud preview: %zu points, %dx%d, %d runs: median %.1f ms wall, %.1f ms thread CPU (min %.1f ms wall)\n",
              points.size(), options.width, options.height, runs, medianOf(wall), medianOf(cpu),
              *std::min_element(wall.begin(), wall.end()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return lidar_sgm::apps::runTool(run, argc, argv); }
