#pragma once
// Inputs for the cross-backend tests: textured pairs with a slanted surface and a step (so every
// stage sees disparity changes), 8- and 16-bit, stored with padded rows, and LiDAR points that
// include several points per pixel and disparities outside the search range.

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace test {

/// An image whose rows are `padding` elements longer than its width (as a cv::Mat ROI's).
template <typename T>
struct PaddedImage {
  std::vector<T> pixels;
  int width = 0;
  int height = 0;
  int stride = 0;
  ImageView<const T> view() const { return ImageView<const T>(pixels.data(), width, height, stride); }
  ImageView<T> view() { return ImageView<T>(pixels.data(), width, height, stride); }
};

template <typename T>
PaddedImage<T> padded(const Image<T>& image, int padding, T fill) {
  PaddedImage<T> out;
  out.width = image.width();
  out.height = image.height();
  out.stride = image.width() + padding;
  out.pixels.assign(static_cast<std::size_t>(out.stride) * out.height, fill);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) out.pixels[static_cast<std::size_t>(y) * out.stride + x] = image(x, y);
  }
  return out;
}

struct BackendScene {
  PaddedImage<std::uint8_t> left8, right8, up8;
  PaddedImage<std::uint16_t> left16, right16, up16;
  LidarPoints lidar;
  double upRatio = 0.37;
};

/// A scene of width x height whose disparities span about [minDisparity, minDisparity + D).
inline BackendScene makeBackendScene(int width, int height, int minDisparity, int numDisparities, unsigned seed) {
  const double lo = minDisparity + 0.15 * numDisparities;
  const double hi = minDisparity + 0.75 * numDisparities;
  // A slanted plane with a nearer box in the middle: slants, a jump and occlusions.
  const auto disparity = [&](double x, double y) {
    const bool box = x > width * 0.4 && x < width * 0.6 && y > height * 0.3;
    return box ? hi : lo + (hi - lo) * 0.4 * y / height;
  };
  const SyntheticStereo s = makeStereo(width, height, disparity, 0, seed);
  BackendScene scene;
  Image<std::uint8_t> up(width, height);
  Image<std::uint16_t> left16(width, height), right16(width, height), up16(width, height);
  std::mt19937 engine(seed);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // The up camera: the left image shifted down by ratio * d rows (clamped), plus noise.
      const int yu = std::max(0, std::min(height - 1, y - static_cast<int>(scene.upRatio * s.disparity(x, y))));
      up(x, y) = static_cast<std::uint8_t>((s.left(x, yu) + engine() % 5u) & 0xFF);
      // 16-bit: 8-bit values spread over 16 bits with low-order noise (ties differ from 8 bits).
      left16(x, y) = static_cast<std::uint16_t>(s.left(x, y) * 256 + engine() % 256u);
      right16(x, y) = static_cast<std::uint16_t>(s.right(x, y) * 256 + engine() % 256u);
      up16(x, y) = static_cast<std::uint16_t>(up(x, y) * 256 + engine() % 256u);
    }
  }
  scene.left8 = padded(s.left, 7, std::uint8_t{0xAB});
  scene.right8 = padded(s.right, 7, std::uint8_t{0xCD});
  scene.up8 = padded(up, 7, std::uint8_t{0xEF});
  scene.left16 = padded(left16, 3, std::uint16_t{0xABCD});
  scene.right16 = padded(right16, 3, std::uint16_t{0x1234});
  scene.up16 = padded(up16, 3, std::uint16_t{0x5678});

  // LiDAR: scan-like rows in the lower two thirds, noisy, with extra points per pixel and some
  // outside the search range (the cost must clamp them exactly as cpu_ref does).
  std::vector<LidarSample> samples;
  std::normal_distribution<double> noise(0.0, 0.5);
  for (int y = height / 3; y < height; y += 3) {
    for (int x = 0; x < width; x += 2) {
      const double d = s.disparity(x, y) + noise(engine);
      samples.push_back({x, y, std::max(1, static_cast<int>(d * kDisparityScale))});
      if (engine() % 7u == 0) samples.push_back({x, y, std::max(1, static_cast<int>((d + 3.0) * kDisparityScale))});
      if (engine() % 13u == 0) {
        samples.push_back({x, y, (minDisparity + numDisparities + 5) * kDisparityScale});
      }
    }
  }
  // And isolated points at random pixels of the upper third and in the four corners: the rows above
  // cover whole runs of columns, which would hide a point's neighbourhood one pixel short on a side.
  std::uniform_int_distribution<int> column(0, width - 1);
  std::uniform_int_distribution<int> row(0, std::max(0, height / 3 - 1));
  const auto isolated = [&](int x, int y) {
    const double d = s.disparity(x, y) + noise(engine);
    samples.push_back({x, y, std::max(1, static_cast<int>(d * kDisparityScale))});
  };
  for (int i = 0; i < std::max(4, width * height / 400); ++i) isolated(column(engine), row(engine));
  for (const int y : {0, height - 1}) {
    for (const int x : {0, width - 1}) isolated(x, y);
  }
  scene.lidar = LidarPoints(width, height, samples);
  return scene;
}

}  // namespace test
}  // namespace lidar_sgm
