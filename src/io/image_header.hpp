#pragma once
/// @file image_header.hpp  (private) What an image file's first bytes say before any decoding: a
/// PNG's size (its IHDR chunk), and the one message for an image over the size limit.

#include <cstddef>
#include <cstdint>
#include <string>

namespace lidar_sgm {
namespace io {
namespace detail {

/// The bytes of a PNG up to its size: the 8-byte signature, then the first chunk, which the
/// format requires to be IHDR: length (bytes 8-11), type (12-15), width and height (16-23,
/// big-endian).
constexpr std::size_t kPngHeaderBytes = 24;

/// What the first kPngHeaderBytes of a file say about it as a PNG.
struct PngHeader {
  std::size_t bytes = 0;     ///< how many of those bytes the file holds (0 when it cannot be opened)
  bool signature = false;    ///< it starts with PNG's signature
  bool ihdr = false;         ///< the signature, all kPngHeaderBytes, and "IHDR" as the first chunk's type
  std::uint32_t width = 0;   ///< IHDR's, when `ihdr`
  std::uint32_t height = 0;  ///< IHDR's, when `ihdr`
};

/// What the first `count` bytes of a file (any count; the first kPngHeaderBytes are read) say.
PngHeader parsePngHeader(const unsigned char* bytes, std::size_t count);

/// Reads at most kPngHeaderBytes of the file at `path`; never throws for what it finds there.
PngHeader readPngHeader(const std::string& path);

/// Throws std::runtime_error "cannot read image '<path>': <w>x<h> pixels is more than the limit
/// of 16384x16384" (kMaxImageSide).
[[noreturn]] void failImageTooLarge(const std::string& path, std::uint64_t width, std::uint64_t height);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
