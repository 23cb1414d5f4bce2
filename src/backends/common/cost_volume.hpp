#pragma once
/// @file cost_volume.hpp  A width x height x numDisparities volume, disparity-innermost.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lidar_sgm {

/// Layout [y][x][d] (d innermost), as libSGM and OpenCV's SGBM keep their cost rows:
/// the per-pixel disparity loop of every stage then reads contiguous memory.
template <typename T>
class CostVolume {
 public:
  CostVolume() = default;
  CostVolume(int width, int height, int numDisparities) { resize(width, height, numDisparities); }

  /// Reallocates only when the size grows; buffers are reused between frames.
  void resize(int width, int height, int numDisparities) {
    width_ = width;
    height_ = height;
    numDisparities_ = numDisparities;
    values_.resize(static_cast<std::size_t>(width) * height * numDisparities);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int numDisparities() const { return numDisparities_; }
  std::size_t size() const { return values_.size(); }

  T* at(int x, int y) { return values_.data() + offset(x, y); }
  const T* at(int x, int y) const { return values_.data() + offset(x, y); }
  T& operator()(int x, int y, int d) { return values_[offset(x, y) + d]; }
  const T& operator()(int x, int y, int d) const { return values_[offset(x, y) + d]; }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }

 private:
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * width_ + x) * numDisparities_;
  }
  int width_ = 0;
  int height_ = 0;
  int numDisparities_ = 0;
  std::vector<T> values_;
};

/// Matching costs (census, LiDAR, fused) fit in 8 bits: every cost is capped at 255.
using MatchingCostVolume = CostVolume<std::uint8_t>;
/// Path costs L_r and their sum S: L_r <= C + P2, so 8 paths of (255 + 4000) fit in 16 bits.
using AggregatedCostVolume = CostVolume<std::uint16_t>;

}  // namespace lidar_sgm
