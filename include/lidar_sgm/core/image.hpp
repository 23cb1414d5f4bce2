#pragma once
/// @file image.hpp  Plain image views and owned images used across the core (no OpenCV, no PCL).

#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

#include "lidar_sgm/core/huge_page_allocator.hpp"

namespace lidar_sgm {

/// Non-owning view of a row-major 2D image. `stride` is counted in elements, not bytes
/// (cv::Mat users pass `mat.step1()`), and may exceed `width` (padded rows).
template <typename T>
struct ImageView {
  T* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;

  ImageView() = default;
  ImageView(T* data_, int width_, int height_, std::ptrdiff_t stride_)
      : data(data_), width(width_), height(height_), stride(stride_) {}
  ImageView(T* data_, int width_, int height_) : ImageView(data_, width_, height_, width_) {}

  /// Views of mutable pixels convert to views of the same, const pixels (as T* to const T*).
  template <typename U = T, typename = std::enable_if_t<!std::is_const<U>::value>>
  operator ImageView<const T>() const {  // NOLINT(google-explicit-constructor): mirrors T* -> const T*
    return ImageView<const T>(data, width, height, stride);
  }

  bool empty() const { return data == nullptr || width <= 0 || height <= 0; }
  T& operator()(int x, int y) const { return data[static_cast<std::ptrdiff_t>(y) * stride + x]; }
  T* row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride; }
};

/// Owned, densely packed image (stride == width); a large one on transparent huge pages.
template <typename T>
class Image {
 public:
  Image() = default;
  Image(int width, int height, T fill = T{})
      : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0 || pixels_.empty(); }
  T* data() { return pixels_.data(); }
  const T* data() const { return pixels_.data(); }
  T& operator()(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const T& operator()(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }

  ImageView<T> view() { return ImageView<T>(pixels_.data(), width_, height_, width_); }
  ImageView<const T> view() const { return ImageView<const T>(pixels_.data(), width_, height_, width_); }

  /// The pixels are kept up to the largest size seen (buffers are reused between frames): a
  /// buffer that alternates between two sizes (the Densifier's matcher runs the half-scale
  /// witness, then the frame) is neither reallocated nor cleared. New pixels are zero only
  /// the first time the buffer grows to them; otherwise the contents are undefined.
  void resize(int width, int height) {
    width_ = width;
    height_ = height;
    const std::size_t n = static_cast<std::size_t>(width) * height;
    if (pixels_.size() < n) pixels_.resize(n);
  }
  void fill(T value) { std::fill(pixels_.begin(), pixels_.begin() + static_cast<std::ptrdiff_t>(pixelCount()), value); }

 private:
  std::size_t pixelCount() const {
    return width_ <= 0 || height_ <= 0 ? 0 : static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  }

  int width_ = 0;
  int height_ = 0;
  HugePageVector<T> pixels_;  // a frame-sized image lies on huge pages (huge_page_allocator.hpp)
};

/// 8-bit color of one pixel (red, green, blue), e.g. the image that colors a dense cloud.
struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

/// In-memory disparities are int16 fixed point with 4 fractional bits (x16), as in OpenCV/libSGM.
constexpr int kDisparityFractionBits = 4;
constexpr int kDisparityScale = 1 << kDisparityFractionBits;
/// Marks a pixel without an estimate (also "no LiDAR point" in sparse disparity images).
/// One value for every minDisparity, unlike OpenCV (below), so a disparity image needs no
/// parameters beside it to be read.
constexpr std::int16_t kInvalidDisparity = std::numeric_limits<std::int16_t>::min();
/// OpenCV StereoSGBM's invalid x16 value, (minDisparity - 1) * 16, one step below its search
/// range; io::toOpenCvDisparity() converts our images to it. In [-8208, 8176] for
/// minDisparity in [-512, 512].
constexpr int openCvInvalidDisparity16(int minDisparity) { return (minDisparity - 1) * kDisparityScale; }

/// A gray image of 8 or 16 bits per pixel (census only compares intensities).
struct GrayImageView {
  ImageView<const std::uint8_t> gray8;
  ImageView<const std::uint16_t> gray16;
  GrayImageView() = default;
  GrayImageView(ImageView<const std::uint8_t> image) : gray8(image) {}    // NOLINT: view conversion
  GrayImageView(ImageView<const std::uint16_t> image) : gray16(image) {}  // NOLINT: view conversion
  GrayImageView(ImageView<std::uint8_t> image) : gray8(image) {}          // NOLINT: view conversion
  GrayImageView(ImageView<std::uint16_t> image) : gray16(image) {}        // NOLINT: view conversion
  bool empty() const { return gray8.empty() && gray16.empty(); }
  int width() const { return gray8.empty() ? gray16.width : gray8.width; }
  int height() const { return gray8.empty() ? gray16.height : gray8.height; }
};

/// Rows [begin, end) of `image`, the same pixels (0 <= begin <= end <= height).
template <typename T>
ImageView<T> rowsOf(ImageView<T> image, int begin, int end) {
  return ImageView<T>(image.row(begin), image.width, end - begin, image.stride);
}
inline GrayImageView rowsOf(const GrayImageView& image, int begin, int end) {
  GrayImageView rows;
  if (!image.gray8.empty()) rows.gray8 = rowsOf(image.gray8, begin, end);
  if (!image.gray16.empty()) rows.gray16 = rowsOf(image.gray16, begin, end);
  return rows;
}

}  // namespace lidar_sgm
