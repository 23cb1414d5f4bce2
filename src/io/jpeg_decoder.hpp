#pragma once
/// @file jpeg_decoder.hpp  (private) JPEG in through libjpeg, as cv::imread(IMREAD_UNCHANGED)
/// decodes it: a gray JPEG as one 8-bit channel, a color one as BGR, the default (islow) DCT, no
/// EXIF rotation. Why not OpenCV's imgcodecs: png_codec.hpp.

#include <cstddef>
#include <cstdint>

#include <opencv2/core.hpp>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Throws std::runtime_error "<libjpeg's reason>" for a file it cannot decode, and for CMYK
/// JPEGs (which no camera rig writes); the caller names the file.
cv::Mat decodeJpeg(const std::uint8_t* bytes, std::size_t size);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
