#include "bench_frame.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace lidar_sgm {
namespace bench {

Frame makeSyntheticFrame(int width, int height) {
  Frame f;
  f.left = Image<std::uint8_t>(width, height);
  f.right = Image<std::uint8_t>(width, height);
  f.synthetic = true;
  f.source = "synthetic (random texture shifted 20 px, LiDAR every 2nd pixel of every 6th row, lower 2/3)";
  std::mt19937 engine(1);
  std::vector<LidarSample> samples;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) f.left(x, y) = static_cast<std::uint8_t>(engine() % 256u);
    for (int x = 0; x < width; ++x) f.right(x, y) = f.left(std::min(width - 1, x + 20), y);
    if (y > height / 3 && y % 6 == 0) {
      for (int x = 0; x < width; x += 2) samples.push_back({x, y, 20 * kDisparityScale});
    }
  }
  f.lidar = LidarPoints(width, height, samples);
  return f;
}

LidarPoints scaledLidar(const LidarPoints& lidar, int width, int height) {
  const double sx = static_cast<double>(width) / lidar.width();
  const double sy = static_cast<double>(height) / lidar.height();
  std::vector<LidarSample> samples;
  samples.reserve(lidar.size());
  for (int y = 0; y < lidar.height(); ++y) {
    for (int x = 0; x < lidar.width(); ++x) {
      for (const int* d = lidar.begin(x, y); d != lidar.end(x, y); ++d) {
        const int xs = std::min(width - 1, static_cast<int>((x + 0.5) * sx));
        const int ys = std::min(height - 1, static_cast<int>((y + 0.5) * sy));
        // At least 1/16 px: a point in front of the camera stays in front of it.
        const int d16 = std::max(1, static_cast<int>(std::lround(*d * sx)));
        samples.push_back({xs, ys, d16});
      }
    }
  }
  return LidarPoints(width, height, samples);
}

}  // namespace bench
}  // namespace lidar_sgm
