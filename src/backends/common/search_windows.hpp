#pragma once
/// @file search_windows.hpp  Per-pixel disparity search windows and the volumes stored on them.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

/// Which disparities each pixel searches: the indices [first(x, y), first(x, y) + count(x, y)) of
/// the frame's range [0, numDisparities) (index d is the disparity minDisparity + d). A window is
/// never empty and never leaves the range; counts are multiples of 16 (whole SIMD vectors) when
/// numDisparities is.
class SearchWindows {
 public:
  /// Every pixel searches the full range [0, numDisparities): the ungated search.
  void resizeFull(int width, int height, int numDisparities) {
    numDisparities_ = numDisparities;
    first_.resize(width, height);
    count_.resize(width, height);
    first_.fill(0);
    count_.fill(static_cast<std::int16_t>(numDisparities));
  }

  /// Sized for a frame, the windows left as they were: for a caller that sets every pixel.
  void resize(int width, int height, int numDisparities) {
    numDisparities_ = numDisparities;
    first_.resize(width, height);
    count_.resize(width, height);
  }

  int width() const { return first_.width(); }
  int height() const { return first_.height(); }
  int numDisparities() const { return numDisparities_; }
  int first(int x, int y) const { return first_(x, y); }
  int count(int x, int y) const { return count_(x, y); }
  bool contains(int x, int y, int d) const { return d >= first(x, y) && d < first(x, y) + count(x, y); }
  /// Every pixel's first index and count as images (a backend that uploads them).
  ImageView<const std::int16_t> firsts() const { return first_.view(); }
  ImageView<const std::int16_t> counts() const { return count_.view(); }
  /// The windows of row y, for a backend that walks rows: first and count of pixel x at [x].
  const std::int16_t* firstRow(int y) const { return first_.view().row(y); }
  const std::int16_t* countRow(int y) const { return count_.view().row(y); }
  /// Row y's windows to write whole (a caller that sets every pixel of the row).
  std::int16_t* firstRowToSet(int y) { return first_.view().row(y); }
  std::int16_t* countRowToSet(int y) { return count_.view().row(y); }
  void set(int x, int y, int first, int count) {
    first_(x, y) = static_cast<std::int16_t>(first);
    count_(x, y) = static_cast<std::int16_t>(count);
  }

  /// Working storage of lidarSearchWindows, kept with the windows so that a frame of a size seen
  /// before allocates nothing: the extremes of each pixel's points over +-1 column (W x H), and
  /// one row of their extremes over the rows around it (lidarSearchWindows' own; a caller that
  /// splits rows among threads brings one per thread); x16 disparities clamped to 16 bits (twice
  /// the lanes of int, and native 16-bit min and max in every SIMD set).
  struct Scratch {
    std::vector<std::int16_t> lowest16, highest16, rowLowest16, rowHighest16;
  };
  Scratch& scratch() { return scratch_; }
  const Scratch& scratch() const { return scratch_; }

 private:
  int numDisparities_ = 0;
  Image<std::int16_t> first_;
  Image<std::int16_t> count_;
  Scratch scratch_;
};

/// A volume holding, for each pixel, only the entries of its search window, pixels in raster
/// order and each window's disparities contiguous (d innermost, as CostVolume): the gated
/// search's memory traffic shrinks with its windows.
template <typename T>
class WindowedVolume {
 public:
  /// Lays the volume out on `windows` (which must outlive the volume's use of it).
  void resize(const SearchWindows& windows) {
    windows_ = &windows;
    width_ = windows.width();
    offsets_.resize(static_cast<std::size_t>(windows.width()) * windows.height() + 1);
    std::size_t total = 0;
    for (int y = 0; y < windows.height(); ++y) {
      for (int x = 0; x < width_; ++x) {
        offsets_[static_cast<std::size_t>(y) * width_ + x] = total;
        total += static_cast<std::size_t>(windows.count(x, y));
      }
    }
    offsets_.back() = total;
    values_.resize(total);
  }

  const SearchWindows& windows() const { return *windows_; }
  int width() const { return windows_->width(); }
  int height() const { return windows_->height(); }
  int numDisparities() const { return windows_->numDisparities(); }
  std::size_t size() const { return values_.size(); }

  /// The entries of pixel (x, y): at(x, y)[k] is disparity index first(x, y) + k.
  T* at(int x, int y) { return values_.data() + offsets_[static_cast<std::size_t>(y) * width_ + x]; }
  const T* at(int x, int y) const { return values_.data() + offsets_[static_cast<std::size_t>(y) * width_ + x]; }
  /// The entry of disparity index d, which must lie in the pixel's window.
  T& operator()(int x, int y, int d) { return at(x, y)[d - windows_->first(x, y)]; }
  const T& operator()(int x, int y, int d) const { return at(x, y)[d - windows_->first(x, y)]; }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }

 private:
  const SearchWindows* windows_ = nullptr;
  int width_ = 0;
  std::vector<std::size_t> offsets_;
  std::vector<T> values_;
};

using WindowedMatchingCost = WindowedVolume<std::uint8_t>;
using WindowedAggregatedCost = WindowedVolume<std::uint16_t>;

}  // namespace lidar_sgm
