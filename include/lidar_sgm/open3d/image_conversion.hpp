#pragma once
/// @file image_conversion.hpp  Open3D images <-> lidar_sgm images: what matching (gray levels)
/// and coloring (8-bit RGB) need from an open3d::geometry::Image, and Open3D images of the
/// library's results. Accepted: 1 (gray), 3 (RGB) or 4 (RGBA, alpha ignored) channels of 8- or
/// 16-bit unsigned values; anything else (float images, 2 channels) throws
/// std::invalid_argument naming the format.

#include <cstdint>
#include <memory>

#include <open3d/geometry/Image.h>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

/// A view of a 1-channel, 8- or 16-bit Open3D image, without a copy (valid while `image` lives
/// and is not resized). Throws std::invalid_argument for any other format.
GrayImageView grayView(const ::open3d::geometry::Image& image);

/// The gray levels of an Open3D image, at its bit depth: a 1-channel image as it is (copied),
/// RGB(A) by the BT.601 weights in OpenCV's fixed point, so that an 8-bit pair given to Open3D
/// matches as the same pair read by the tools (cv::cvtColor RGB2GRAY, exactly). At 16 bits
/// OpenCV's vector code rounds differently: its gray and this one differ by up to 2 of 65535.
class Open3dGray {
 public:
  explicit Open3dGray(const ::open3d::geometry::Image& image);
  /// 8- or 16-bit, as the source image.
  GrayImageView view() const;

 private:
  Image<std::uint8_t> gray8_;
  Image<std::uint16_t> gray16_;
};

/// 8-bit RGB of an Open3D image, for the output colors: RGB(A) as it is, gray replicated; a
/// 16-bit image scaled by 1/257, rounded (what the tools' io::toColor() does).
Image<Rgb8> toRgb8(const ::open3d::geometry::Image& image);

/// Open3D images of lidar_sgm images (copied): 8-bit gray, 16-bit gray, 8-bit RGB and float
/// (e.g. Densifier::depth() in metres, as open3d::geometry::RGBDImage takes depth).
std::shared_ptr<::open3d::geometry::Image> toOpen3dImage(ImageView<const std::uint8_t> image);
std::shared_ptr<::open3d::geometry::Image> toOpen3dImage(ImageView<const std::uint16_t> image);
std::shared_ptr<::open3d::geometry::Image> toOpen3dImage(ImageView<const Rgb8> image);
std::shared_ptr<::open3d::geometry::Image> toOpen3dImage(ImageView<const float> image);

}  // namespace lidar_sgm
