#pragma once
/// @file impl/sgm_densification.hpp  Template body of SGMDensification. Include it for point
/// types other than the explicitly instantiated ones (or define PCL_NO_PRECOMPILE).

#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include <pcl/console/print.h>
#include <pcl/type_traits.h>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {

namespace detail {

/// Gray from RGB with OpenCV's fixed-point BT.601 weights (cvtColor BGR2GRAY on 8-bit images:
/// 0.299, 0.587, 0.114 scaled by 2^15), so a pair given as PCL images matches the same pair
/// read by the tools (test_kitti_frames checks it against cv::cvtColor).
inline std::uint8_t grayFromRgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return static_cast<std::uint8_t>((r * 9798 + g * 19235 + b * 3735 + (1 << 14)) >> 15);
}

inline Image<std::uint8_t> grayImage(const pcl::PointCloud<pcl::RGB>& image) {
  Image<std::uint8_t> gray(static_cast<int>(image.width), static_cast<int>(image.height));
  for (int y = 0; y < gray.height(); ++y) {
    for (int x = 0; x < gray.width(); ++x) {
      const pcl::RGB& p = image.at(x, y);
      gray(x, y) = grayFromRgb(p.r, p.g, p.b);
    }
  }
  return gray;
}

inline Image<Rgb8> colorImage(const pcl::PointCloud<pcl::RGB>& image) {
  Image<Rgb8> color(static_cast<int>(image.width), static_cast<int>(image.height));
  for (int y = 0; y < color.height(); ++y) {
    for (int x = 0; x < color.width(); ++x) {
      const pcl::RGB& p = image.at(x, y);
      color(x, y) = Rgb8{p.r, p.g, p.b};
    }
  }
  return color;
}

inline bool isOrganizedImage(const pcl::PointCloud<pcl::RGB>& image) {
  return image.height > 1 && image.width > 1 && image.size() == std::size_t{image.width} * image.height;
}

}  // namespace detail

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::setInputCloud(const typename PointCloudIn::ConstPtr& cloud) {
  if (filteredSinceCloud_) {
    // A new frame: what the last one was given and this one was not is not this frame's.
    if (!pairGivenSinceFilter_) {
      densifier_.clearStereoPair();
      pairColor_ = Image<Rgb8>();
      colorChanged_ = true;
      pairError_.clear();
    }
    if (!colorGivenSinceFilter_) {
      explicitColor_ = Image<Rgb8>();
      colorChanged_ = true;
      colorError_.clear();
    }
    filteredSinceCloud_ = false;
  }
  pcl::PCLBase<PointInT>::setInputCloud(cloud);
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::setStereoPair(const ImageCloud& left, const ImageCloud& right) {
  pairGivenSinceFilter_ = true;
  pairColor_ = Image<Rgb8>();
  colorChanged_ = true;
  // Invalid images are remembered as an error for filter() (PCL setters do not throw).
  if (!detail::isOrganizedImage(left) || !detail::isOrganizedImage(right)) {
    densifier_.clearStereoPair();
    pairError_ = "setStereoPair: the images must be organized clouds (width x height, height > 1)";
    return;
  }
  const Image<std::uint8_t> l = detail::grayImage(left);
  const Image<std::uint8_t> r = detail::grayImage(right);
  try {
    densifier_.setStereoPair(l.view(), r.view());
    pairError_.clear();
  } catch (const std::exception& e) {
    densifier_.clearStereoPair();
    pairError_ = e.what();
    return;
  }
  pairColor_ = detail::colorImage(left);
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::setStereoPair(const GrayImageView& left, const GrayImageView& right) {
  pairGivenSinceFilter_ = true;
  // A gray pair colors through the densifier's gray fallback unless a color image is set.
  pairColor_ = Image<Rgb8>();
  colorChanged_ = true;
  try {
    densifier_.setStereoPair(left, right);
    pairError_.clear();
  } catch (const std::exception& e) {
    densifier_.clearStereoPair();
    pairError_ = e.what();
  }
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::clearStereoPair() {
  pairGivenSinceFilter_ = true;
  densifier_.clearStereoPair();
  pairColor_ = Image<Rgb8>();
  colorChanged_ = true;
  pairError_.clear();
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::setColorImage(const ImageCloud& image) {
  colorGivenSinceFilter_ = true;
  explicitColor_ = Image<Rgb8>();
  colorChanged_ = true;
  if (!detail::isOrganizedImage(image)) {
    colorError_ = "setColorImage: the image must be an organized cloud (width x height, height > 1)";
    return;
  }
  explicitColor_ = detail::colorImage(image);
  colorError_.clear();
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::useFrameImages() {
  // The images given for this frame are now used: the next setInputCloud() starts a new one.
  pairGivenSinceFilter_ = false;
  colorGivenSinceFilter_ = false;
  filteredSinceCloud_ = true;
  // Handed over (a copy) only when it changed: a parameter sweep's frames do not copy it again.
  if (colorChanged_) {
    const Image<Rgb8>& color = explicitColor_.empty() ? pairColor_ : explicitColor_;
    densifier_.setColorImage(std::as_const(color).view());  // empty: the pair's gray, or none
    colorChanged_ = false;
  }
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::fail(PointCloudOut& output, const std::string& message) {
  lastError_ = message;
  projected_ = geometry::ProjectedLidar();  // not the previous frame's
  PCL_ERROR("[lidar_sgm::%s::filter] %s\n", getClassName().c_str(), message.c_str());
  output.clear();
  output.width = 0;
  output.height = 0;
  output.is_dense = true;
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::takeProjected() {
  // The densifier saw points_, the indexed points in index order: its sourceIndex counts
  // positions in *indices_, which users of setIndices() cannot trace back without the list.
  projected_ = densifier_.projected();
  for (std::size_t& source : projected_.sourceIndex) source = static_cast<std::size_t>((*indices_)[source]);
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::mapLidarPixels() {
  if constexpr (pcl::traits::has_intensity_v<PointInT>) {
    lidarPixel_.resize(projected_.width, projected_.height);
    lidarPixel_.fill(-1);
    // The nearest point (largest disparity) wins a shared pixel, as in sparseDisparity().
    for (std::size_t i = 0; i < projected_.samples.size(); ++i) {
      const LidarSample& s = projected_.samples[i];
      std::int32_t& winner = lidarPixel_(s.x, s.y);
      if (winner < 0 || s.disparity16 > projected_.samples[static_cast<std::size_t>(winner)].disparity16) {
        winner = static_cast<std::int32_t>(i);
      }
    }
  }
}

template <typename PointInT, typename PointOutT>
float SGMDensification<PointInT, PointOutT>::intensityAt(int x, int y) const {
  if constexpr (pcl::traits::has_intensity_v<PointInT>) {
    const std::int32_t sample = lidarPixel_(x, y);
    if (sample >= 0) return (*input_)[projected_.sourceIndex[static_cast<std::size_t>(sample)]].intensity;
  }
  Rgb8 c;
  if (densifier_.colorAt(x, y, c)) return static_cast<float>(detail::grayFromRgb(c.r, c.g, c.b));
  return std::numeric_limits<float>::quiet_NaN();
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::filter(PointCloudOut& output) {
  lastError_.clear();
  useFrameImages();
  if (!pairError_.empty() || !colorError_.empty()) {
    fail(output, pairError_.empty() ? colorError_ : pairError_);
    return;
  }
  if (!input_) {
    fail(output, "no input cloud: call setInputCloud() first");
    return;
  }
  if (!initCompute()) {
    fail(output, "the input cloud or its indices are invalid");
    return;
  }
  points_.clear();
  points_.reserve(indices_->size());
  for (const auto index : *indices_) {
    const PointInT& p = (*input_)[index];
    points_.emplace_back(p.x, p.y, p.z);
  }
  const pcl::PCLHeader header = input_->header;  // output may alias nothing, but copy first anyway
  const geometry::DenseCloud* dense = nullptr;
  try {
    dense = &densifier_.run(points_);
  } catch (const std::exception& e) {
    deinitCompute();
    fail(output, e.what());
    return;
  }
  takeProjected();
  const Image<std::uint8_t>& confidence = densifier_.confidence();
  if constexpr (pcl::traits::has_intensity_v<PointOutT>) mapLidarPixels();

  output.header = header;
  if (densifier_.reprojectionOptions().frame == geometry::OutputFrame::Camera) output.header.frame_id = cameraFrameId_;
  if (output.points.capacity() < dense->size()) {
    output.clear();
    reserveOnHugePages(output.points, dense->size());  // a frame's cloud: tens of MB, written once
  }
  output.resize(dense->size());  // a reused cloud: only the points beyond its last size are new
  output.width = static_cast<std::uint32_t>(dense->width);
  output.height = static_cast<std::uint32_t>(dense->height);
  output.is_dense = dense->isDense;
  // The points in parallel on the Densifier's threads (the PCL cloud is written once, ~30 bytes a
  // pixel, and colors and confidences are looked up per point).
  densifier_.parallelFor(dense->size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) convertPoint(*dense, confidence, i, output[i]);
  });
  deinitCompute();
}

template <typename PointInT, typename PointOutT>
void SGMDensification<PointInT, PointOutT>::convertPoint(const geometry::DenseCloud& dense,
                                                         const Image<std::uint8_t>& confidence, std::size_t i,
                                                         PointOutT& q) const {
  constexpr bool kHasIntensity = pcl::traits::has_intensity_v<PointOutT>;
  constexpr bool kHasConfidence = pcl::traits::has_field<PointOutT, pcl::fields::confidence>::value;
  // From a default point: a field this frame does not write (color without an image) must not
  // keep what an earlier frame wrote into a reused output cloud.
  q = PointOutT();
  const geometry::PixelIndex pixel = dense.pixels[i];
  q.x = dense.points[i].x();
  q.y = dense.points[i].y();
  q.z = dense.points[i].z();
  if constexpr (pcl::traits::has_color_v<PointOutT>) {
    Rgb8 c;
    if (densifier_.colorAt(pixel.x, pixel.y, c)) {
      q.r = c.r;
      q.g = c.g;
      q.b = c.b;
    }
  }
  if constexpr (kHasIntensity) q.intensity = intensityAt(pixel.x, pixel.y);
  if constexpr (kHasConfidence) {
    q.confidence = confidence.empty() ? std::numeric_limits<float>::quiet_NaN()
                                      : static_cast<float>(confidence(pixel.x, pixel.y)) / 255.0f;
  }
}

}  // namespace lidar_sgm

/// For PCL_INSTANTIATE_PRODUCT(SGMDensification, (inputs)(outputs)), as PCL's own impl files.
#define PCL_INSTANTIATE_SGMDensification(In, Out) template class lidar_sgm::SGMDensification<In, Out>;
