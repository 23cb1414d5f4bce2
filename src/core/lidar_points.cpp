#include "lidar_sgm/core/lidar_points.hpp"

#include <sstream>
#include <stdexcept>

namespace lidar_sgm {

LidarPoints::LidarPoints(int width, int height, const std::vector<LidarSample>& samples) {
  assign(width, height, samples);
}

void LidarPoints::assign(int width, int height, const std::vector<LidarSample>& samples) {
  width_ = 0;  // empty until the samples are checked: a throw leaves no half-built points
  height_ = 0;
  disparities16_.clear();
  pointPixels_.clear();
  if (width <= 0 || height <= 0) {
    std::ostringstream os;
    os << "LiDAR points: image size " << width << "x" << height << " is empty";
    throw std::invalid_argument(os.str());
  }
  pixelStart_.assign(static_cast<std::size_t>(width) * height + 1, 0);  // reuses the capacity
  const auto pixelOf = [width](int x, int y) { return static_cast<std::size_t>(y) * width + x; };
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
    ++pixelStart_[pixelOf(s.x, s.y)];
  }
  // Counting sort into compressed rows: the prefix sums give each pixel's end, which serves as
  // the pixel's cursor while the samples are placed from the last to the first (no copy of the
  // offsets), so that a pixel's samples keep their order and the cursor ends at its first slot.
  const std::size_t pixels = pixelStart_.size() - 1;
  for (std::size_t i = 1; i < pixels; ++i) pixelStart_[i] += pixelStart_[i - 1];
  pixelStart_[pixels] = static_cast<int>(samples.size());
  disparities16_.resize(samples.size());
  pointPixels_.resize(samples.size());
  for (std::size_t i = samples.size(); i-- > 0;) {
    const LidarSample& s = samples[i];
    const std::size_t pixel = pixelOf(s.x, s.y);
    const auto slot = static_cast<std::size_t>(--pixelStart_[pixel]);
    pointPixels_[slot] = static_cast<int>(pixel);
    disparities16_[slot] = s.disparity16;
  }
  width_ = width;
  height_ = height;
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
