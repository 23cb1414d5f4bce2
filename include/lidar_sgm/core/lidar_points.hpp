#pragma once
/// @file lidar_points.hpp  LiDAR points projected into the left rectified image, kept per pixel.

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

/// One projected LiDAR point: pixel (x, y) of the left rectified image and its virtual
/// disparity d_P = f*b/z_P (Eq. 3) in x16 fixed point.
struct LidarSample {
  int x = 0;
  int y = 0;
  int disparity16 = 0;
};

/// Projected LiDAR points bucketed per pixel. Several points may fall into one pixel (the LiDAR
/// sees from another viewpoint than the camera); all of them are kept, because Eq. 4 takes the
/// minimum cost over every point associated with a pixel.
class LidarPoints {
 public:
  LidarPoints() = default;

  /// Throws std::invalid_argument naming the first sample outside the image or with a
  /// non-positive disparity (a point at or behind the camera).
  LidarPoints(int width, int height, const std::vector<LidarSample>& samples);

  /// The same in place, reusing this object's buffers (a pipeline that builds the points every
  /// frame allocates and clears no new pages). On a throw the object is left empty.
  void assign(int width, int height, const std::vector<LidarSample>& samples);

  /// Every valid pixel (!= kInvalidDisparity, > 0) of a sparse x16 disparity image is one point.
  static LidarPoints fromDisparityImage(ImageView<const std::int16_t> sparse);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return disparities16_.size(); }
  bool empty() const { return disparities16_.empty(); }

  /// The x16 disparities of the points that fall into pixel (x, y): [begin, end).
  const int* begin(int x, int y) const { return disparities16_.data() + pixelStart_[index(x, y)]; }
  const int* end(int x, int y) const { return disparities16_.data() + pixelStart_[index(x, y) + 1]; }
  int count(int x, int y) const { return static_cast<int>(end(x, y) - begin(x, y)); }

  /// The compressed rows themselves, for a backend that copies them as they are (to a GPU):
  /// pixel (x, y) holds disparities16()[pixelStarts()[y * width() + x] .. pixelStarts()[... + 1]).
  const HugePageVector<int>& pixelStarts() const { return pixelStart_; }
  const std::vector<int>& disparities16() const { return disparities16_; }
  /// The pixel y * width() + x of each point of disparities16(), in the same (ascending) order:
  /// with it a backend rebuilds pixelStarts() where the points are (8 bytes a point, not 4 a pixel).
  const std::vector<int>& pointPixels() const { return pointPixels_; }

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int width_ = 0;
  int height_ = 0;
  HugePageVector<int> pixelStart_;      ///< width*height+1 offsets into disparities16_ (CSR)
  std::vector<int> disparities16_;   ///< per pixel, in the order the samples were given
  std::vector<int> pointPixels_;     ///< the pixel index of each entry of disparities16_
};

}  // namespace lidar_sgm
