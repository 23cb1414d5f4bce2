// What a frame costs a process that densifies at a camera's rate, as a robot's node does: one
// frame every PERIOD ms through SGMDensification, the caller asleep in between. Prints the medians
// of the frame's wall time, of the process's CPU time during the frame and of the process's CPU
// time while the caller sleeps. The last is the OpenMP runtime's: after a parallel region its
// workers spin before they sleep (libgomp: GOMP_SPINCOUNT, OMP_WAIT_POLICY), and that CPU is taken
// from whatever else the machine runs between frames (docs/LIBRARY.md, "Threads between frames").
//
//   build/bench/frame_period_cpu [PERIOD_MS] [FRAMES] [DIR NAME]   (default: 100 ms, 30 frames of data/sample 000000)
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "densify/densify_options.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"
#include "thread_cpu.hpp"

namespace {

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  const int period = argc > 1 ? std::atoi(argv[1]) : 100;
  const int frames = argc > 2 ? std::atoi(argv[2]) : 30;
  const std::string dir = argc > 4 ? argv[3] : LIDAR_SGM_SAMPLE_DIR;
  const std::string name = argc > 4 ? argv[4] : "000000";
  if (period < 1 || frames < 1) {
    std::fprintf(stderr, "usage: %s [PERIOD_MS >= 1] [FRAMES >= 1] [DIR NAME]\n", argv[0]);
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
  std::vector<double> busy;
  std::vector<double> idle;
  using Clock = std::chrono::steady_clock;
  auto next = Clock::now();
  for (int i = 0; i <= frames; ++i) {  // frame 0 warms up
    std::this_thread::sleep_until(next);
    next += std::chrono::milliseconds(period);
    const double cpu0 = processCpuMs();
    const auto start = Clock::now();
    lidar_sgm::apps::setImages(sgm, left, right);
    sgm.filter(dense);
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const double cpu1 = processCpuMs();
    // The caller sleeps until the next period begins; only the runtime's threads can run now.
    std::this_thread::sleep_until(next);
    const double cpu2 = processCpuMs();
    if (i == 0) continue;
    walls.push_back(wall);
    busy.push_back(cpu1 - cpu0);
    idle.push_back(cpu2 - cpu1);
  }
  using lidar_sgm::bench::medianOf;
  std::printf("%s: %zu points, one frame every %d ms, %d frames (the caller sleeps between them)\n", name.c_str(),
              dense.size(), period, frames);
  std::printf("median frame %.1f ms, process CPU during the frame %.1f ms, process CPU while the caller sleeps %.1f ms\n",
              medianOf(walls), medianOf(busy), medianOf(idle));
  return 0;
}
