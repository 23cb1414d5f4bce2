// lidar_sgm_bench: time per frame and per stage, core only (builds without OpenCV/PCL).
// Prints a settings block, then the median over -runs frames after one warm-up frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "lidar_sgm/core/matcher.hpp"

namespace {

using lidar_sgm::Image;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// A textured pair with a known shift and a 64-beam-like sparse LiDAR (about 5 % of pixels):
// the work per frame does not depend on the image content, only on the sizes.
struct Frame {
  Image<std::uint8_t> left, right;
  lidar_sgm::LidarPoints lidar;
};

Frame makeFrame(int width, int height) {
  Frame f{Image<std::uint8_t>(width, height), Image<std::uint8_t>(width, height), {}};
  std::mt19937 engine(1);
  std::vector<lidar_sgm::LidarSample> samples;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) f.left(x, y) = static_cast<std::uint8_t>(engine() % 256u);
    for (int x = 0; x < width; ++x) f.right(x, y) = f.left(std::min(width - 1, x + 20), y);
    if (y > height / 3 && y % 6 == 0) {
      for (int x = 0; x < width; x += 2) samples.push_back({x, y, 20 * lidar_sgm::kDisparityScale});
    }
  }
  f.lidar = lidar_sgm::LidarPoints(width, height, samples);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 1242, height = 375, runs = 5;
  std::string backendName = "cpu_ref", mode = "fused";
  lidar_sgm::Parameters params;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "-width") width = std::stoi(value);
    else if (key == "-height") height = std::stoi(value);
    else if (key == "-runs") runs = std::stoi(value);
    else if (key == "-backend") backendName = value;
    else if (key == "-mode") mode = value;
    else if (key == "-num_disparities") params.numDisparities = std::stoi(value);
    else if (key == "-paths") params.paths = std::stoi(value);
    else {
      std::fprintf(stderr, "usage: %s [-width 1242] [-height 375] [-runs 5] [-backend cpu_ref] "
                   "[-mode fused|stereo|lidar] [-num_disparities 128] [-paths 4]\n", argv[0]);
      return 1;
    }
  }
  try {
    auto matcher = lidar_sgm::Matcher::create(lidar_sgm::backendFromString(backendName), params);
    const Frame frame = makeFrame(width, height);
    Image<std::int16_t> out(width, height);
    const bool stereo = mode != "lidar";
    const bool withLidar = mode != "stereo";
    std::printf("lidar_sgm_bench\n  machine: %u hardware threads\n  image: %dx%d, disparities %d, paths %d\n"
                "  backend: %s, mode: %s, runs: %d (+1 warm-up)\n",
                std::thread::hardware_concurrency(), width, height, params.numDisparities, params.paths,
                lidar_sgm::toString(matcher->backend()).c_str(), mode.c_str(), runs);
    std::vector<double> total, census, stereoCost, costs, aggregate, select, lr, med;
    for (int r = 0; r <= runs; ++r) {
      const auto start = std::chrono::steady_clock::now();
      matcher->compute(frame.left.view(), stereo ? lidar_sgm::GrayImageView(frame.right.view()) : lidar_sgm::GrayImageView(),
                       withLidar ? &frame.lidar : nullptr, out.view());
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (r == 0) continue;
      const lidar_sgm::StageTimings& t = matcher->lastTimings();
      total.push_back(ms);
      census.push_back(t.census);
      stereoCost.push_back(t.censusCost);
      costs.push_back(t.lidarCost + t.fuseCosts);
      aggregate.push_back(t.aggregatePaths);
      select.push_back(t.selectDisparity);
      lr.push_back(t.leftRightCheck);
      med.push_back(t.medianFilter);
    }
    std::printf("  median ms: frame %.1f | census %.1f  censusCost %.1f  lidarCost+fuse %.1f  aggregatePaths %.1f  select %.1f  "
                "lr-check %.1f  median %.1f\n",
                median(total), median(census), median(stereoCost), median(costs), median(aggregate), median(select), median(lr), median(med));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "Error: %s\n", e.what());
    return 1;
  }
  return 0;
}
