#pragma once
// The frame the benchmark matches: an 8-bit gray pair and its sparse LiDAR, whatever its source.
// Core only, so that the bench builds (with -synthetic) where OpenCV is absent.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace bench {

struct Frame {
  Image<std::uint8_t> left;
  Image<std::uint8_t> right;
  LidarPoints lidar;
  std::string source;  ///< what was loaded, for the settings block
  std::vector<std::pair<std::string, std::string>> files;  ///< (role, path) of each file read
  bool synthetic = false;

  int width() const { return left.width(); }
  int height() const { return left.height(); }
};

/// A textured pair with a known shift and a 64-beam-like sparse LiDAR (about 5 % of pixels).
/// The work per frame does not depend on the image content, only on the sizes, so this frame
/// times the same as a real one of its size (when no real one can be read).
Frame makeSyntheticFrame(int width, int height);

/// The points of `lidar` moved to a `width` x `height` image: each point to the pixel its
/// centre falls in, its disparity scaled by the horizontal factor (a disparity is a column
/// offset). Points that collide stay, as LidarPoints keeps every point of a pixel.
LidarPoints scaledLidar(const LidarPoints& lidar, int width, int height);

}  // namespace bench
}  // namespace lidar_sgm
