// Image sizes from file headers: the PNG check readImage runs before decoding, and imageSize(),
// which gives a PNG's size without decoding it at all.
#include "image_header.hpp"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "lidar_sgm/io/file_access.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

std::uint32_t bigEndian32(const unsigned char* bytes) {
  return (static_cast<std::uint32_t>(bytes[0]) << 24) | (static_cast<std::uint32_t>(bytes[1]) << 16) |
         (static_cast<std::uint32_t>(bytes[2]) << 8) | static_cast<std::uint32_t>(bytes[3]);
}

}  // namespace

PngHeader parsePngHeader(const unsigned char* bytes, std::size_t count) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  PngHeader png;
  png.bytes = count < kPngHeaderBytes ? count : kPngHeaderBytes;
  png.signature = png.bytes >= sizeof kSignature && std::memcmp(bytes, kSignature, sizeof kSignature) == 0;
  png.ihdr = png.signature && png.bytes == kPngHeaderBytes && std::memcmp(bytes + 12, "IHDR", 4) == 0;
  if (png.ihdr) {
    png.width = bigEndian32(bytes + 16);
    png.height = bigEndian32(bytes + 20);
  }
  return png;
}

PngHeader readPngHeader(const std::string& path) {
  unsigned char header[kPngHeaderBytes] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(header), sizeof header);
  return parsePngHeader(header, static_cast<std::size_t>(in.gcount()));
}

void failImageTooLarge(const std::string& path, std::uint64_t width, std::uint64_t height) {
  throw std::runtime_error("cannot read image '" + path + "': " + std::to_string(width) + "x" + std::to_string(height) +
                           " pixels is more than the limit of " + std::to_string(kMaxImageSide) + "x" +
                           std::to_string(kMaxImageSide));
}

}  // namespace detail

cv::Size imageSize(const std::string& path) {
  const std::string unreadable = unreadableFileReason(path);
  if (!unreadable.empty()) throw std::runtime_error("cannot read image '" + path + "': " + unreadable);
  const detail::PngHeader png = detail::readPngHeader(path);
  // Only a PNG's size is read from its header; other formats are decoded for it.
  if (!png.signature) return readImage(path).size();
  if (png.bytes < detail::kPngHeaderBytes) {
    throw std::runtime_error("cannot read image '" + path + "': a PNG cut short: " + std::to_string(png.bytes) +
                             " bytes, before its size (bytes 16 to 23)");
  }
  if (!png.ihdr) {
    throw std::runtime_error("cannot read image '" + path +
                             "': not a readable image file (its first PNG chunk is not IHDR)");
  }
  if (png.width == 0 || png.height == 0) {
    throw std::runtime_error("cannot read image '" + path + "': not a readable image file (a PNG of " +
                             std::to_string(png.width) + "x" + std::to_string(png.height) + " pixels)");
  }
  const auto limit = static_cast<std::uint32_t>(kMaxImageSide);
  if (png.width > limit || png.height > limit) detail::failImageTooLarge(path, png.width, png.height);
  return cv::Size(static_cast<int>(png.width), static_cast<int>(png.height));
}

}  // namespace io
}  // namespace lidar_sgm
