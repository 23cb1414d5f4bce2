#include "lidar_sgm/core/lidar_points.hpp"

#include <sstream>
#include <stdexcept>

namespace lidar_sgm {

LidarPoints::LidarPoints(int width, int height, const std::vector<LidarSample>& samples)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    std::ostringstream os;
    os << "LiDAR points: image size " << width << "x" << height << " is empty";
    throw std::invalid_argument(os.str());
  }
  pixelStart_.assign(static_cast<std::size_t>(width) * height + 1, 0);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const LidarSample& s = samples[i];
    if (s.x < 0 || s.x >= width || s.y < 0 || s.y >= height || s.disparity16 <= 0) {
      std::ostringstream os;
      os << "LiDAR point " << i << " at pixel (" << s.x << ", " << s.y << ") with disparity "
         << s.disparity16 / static_cast<double>(kDisparityScale) << " px is "
         << (s.disparity16 <= 0 ? "at or behind the camera (disparity must be > 0)"
                                : "outside the " + std::to_string(width) + "x" +
                                      std::to_string(height) + " image");
      throw std::invalid_argument(os.str());
    }
    ++pixelStart_[index(s.x, s.y) + 1];
  }
  // Counting sort into compressed rows: prefix sums give each pixel's first slot.
  for (std::size_t i = 1; i < pixelStart_.size(); ++i) pixelStart_[i] += pixelStart_[i - 1];
  disparities16_.resize(samples.size());
  pointPixels_.resize(samples.size());
  std::vector<int> next(pixelStart_.begin(), pixelStart_.end() - 1);
  for (const LidarSample& s : samples) {
    const std::size_t pixel = index(s.x, s.y);
    pointPixels_[static_cast<std::size_t>(next[pixel])] = static_cast<int>(pixel);
    disparities16_[static_cast<std::size_t>(next[pixel]++)] = s.disparity16;
  }
}

LidarPoints LidarPoints::fromDisparityImage(ImageView<const std::int16_t> sparse) {
  std::vector<LidarSample> samples;
  for (int y = 0; y < sparse.height; ++y) {
    for (int x = 0; x < sparse.width; ++x) {
      const std::int16_t d = sparse(x, y);
      if (d != kInvalidDisparity && d > 0) samples.push_back({x, y, d});
    }
  }
  return LidarPoints(sparse.width, sparse.height, samples);
}

}  // namespace lidar_sgm
