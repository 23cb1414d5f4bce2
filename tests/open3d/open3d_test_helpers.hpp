#pragma once
// Open3D images and a wall scan for the lidar_sgm::open3d tests.

#include <cstdint>
#include <cstring>
#include <memory>

#include <open3d/geometry/Image.h>
#include <open3d/geometry/PointCloud.h>

#include "geometry/geometry_test_helpers.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace test {

/// An Open3D image of `channels` x `bytes` per pixel, every byte `fill`.
inline ::open3d::geometry::Image open3dImage(int width, int height, int channels, int bytes, std::uint8_t fill = 0) {
  ::open3d::geometry::Image image;
  image.Prepare(width, height, channels, bytes);
  std::memset(image.data_.data(), fill, image.data_.size());
  return image;
}

/// `gray` as an Open3D RGB image (each channel the gray level).
inline ::open3d::geometry::Image open3dRgb(const Image<std::uint8_t>& gray) {
  ::open3d::geometry::Image image = open3dImage(gray.width(), gray.height(), 3, 1);
  for (int y = 0; y < gray.height(); ++y) {
    for (int x = 0; x < gray.width(); ++x) {
      for (int c = 0; c < 3; ++c) *image.PointerAt<std::uint8_t>(x, y, c) = gray(x, y);
    }
  }
  return image;
}

/// A LiDAR-like scan of a wall at `depth` m: every 2nd column, every 4th row of the image.
inline ::open3d::geometry::PointCloud wallScan(const geometry::StereoCalibration& c, double depth) {
  ::open3d::geometry::PointCloud scan;
  for (int v = 2; v < c.height; v += 4) {
    for (int u = 0; u < c.width; u += 2) scan.points_.push_back(lidarPointAt(c, u, v, depth).cast<double>());
  }
  return scan;
}

}  // namespace test
}  // namespace lidar_sgm
