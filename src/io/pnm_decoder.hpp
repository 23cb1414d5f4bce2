#pragma once
/// @file pnm_decoder.hpp  (private) PGM and PPM in (P2, P3, P5, P6), as
/// cv::imread(IMREAD_UNCHANGED) decodes them: maxval > 255 gives 16-bit samples, PPM comes out as
/// BGR; ASCII 8-bit samples are scaled to 0-255 by 255/maxval (clamped to maxval first), binary
/// ones and all 16-bit ones are kept as stored. Why not OpenCV's imgcodecs: png_codec.hpp.

#include <cstddef>
#include <cstdint>

#include <opencv2/core.hpp>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Throws std::runtime_error naming what is wrong (the header, a sample, the end of the data);
/// the caller names the file.
cv::Mat decodePnm(const std::uint8_t* bytes, std::size_t size);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
