#pragma once
/// @file png_codec.hpp  (private) PNG in and out through libpng, with OpenCV's conventions.
///
/// Why not OpenCV's imgcodecs: on Debian it links GDAL, GDCM, OpenEXR and ~130 shared libraries
/// that every tool would load before main() (about 0.12 s of each run, BENCHMARK.md "Start-up"),
/// for the PNGs a rig writes. The pixels and bytes are OpenCV's: BGR(A) channel order, 16-bit
/// samples in native order, and its encoder's settings (tests/io/test_image_codecs.cpp compares
/// both, pixel for pixel and byte for byte).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Decodes a whole PNG held in memory as cv::imread(IMREAD_UNCHANGED) does: gray (1 channel),
/// gray + alpha (4), RGB or palette (3, or 4 with a tRNS chunk), RGBA (4); 8 or 16 bits (1, 2 and
/// 4-bit gray expanded to 8). Throws std::runtime_error "<libpng's reason>" when it is not a
/// readable PNG; the caller names the file.
cv::Mat decodePng(const std::uint8_t* bytes, std::size_t size);

/// Encodes an 8- or 16-bit image of 1, 3 (BGR) or 4 (BGRA) channels as cv::imencode(".png")
/// does: zlib level `compression` 0-9 with the default filters, or, for -1 (OpenCV's default),
/// level 1 with the SUB filter and the RLE strategy. Throws std::invalid_argument for another
/// type or level, std::runtime_error when libpng fails.
std::vector<std::uint8_t> encodePng(const cv::Mat& image, int compression = -1);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
