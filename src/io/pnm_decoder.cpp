#include "pnm_decoder.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <stdexcept>
#include <string>

#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

class Reader {
 public:
  Reader(const std::uint8_t* bytes, std::size_t size) : bytes_(bytes), size_(size) {}

  /// A decimal number after whitespace and '#' comments, and the one byte after its digits
  /// (the header's last number is followed by exactly one whitespace byte before binary data).
  std::uint32_t number(const char* what) {
    for (;;) {
      if (at_ >= size_) fail(std::string("the file ends before its ") + what);
      const int c = bytes_[at_];
      if (c == '#') {
        while (at_ < size_ && bytes_[at_] != '\n' && bytes_[at_] != '\r') ++at_;
      } else if (std::isspace(c) != 0) {
        ++at_;
      } else {
        break;
      }
    }
    if (std::isdigit(bytes_[at_]) == 0) fail(std::string("its ") + what + " is not a number");
    std::uint64_t value = 0;
    while (at_ < size_ && std::isdigit(bytes_[at_]) != 0) {
      value = value * 10 + (bytes_[at_++] - '0');
      if (value > 0xFFFFFFFFu) fail(std::string("its ") + what + " is too large");
    }
    if (at_ < size_) ++at_;  // the separator
    return static_cast<std::uint32_t>(value);
  }

  const std::uint8_t* take(std::size_t count) {
    if (count > size_ - at_) fail("the file ends inside the pixels");
    const std::uint8_t* from = bytes_ + at_;
    at_ += count;
    return from;
  }

  [[noreturn]] static void fail(const std::string& problem) { throw std::runtime_error("a PGM/PPM file: " + problem); }

 private:
  const std::uint8_t* bytes_;
  std::size_t size_;
  std::size_t at_ = 2;  // after "P<n>"
};

}  // namespace

cv::Mat decodePnm(const std::uint8_t* bytes, std::size_t size) {
  if (size < 3 || bytes[0] != 'P' || std::strchr("2356", bytes[1]) == nullptr) Reader::fail("not P2, P3, P5 or P6");
  const bool binary = bytes[1] >= '5';
  const int channels = (bytes[1] == '3' || bytes[1] == '6') ? 3 : 1;
  Reader in(bytes, size);
  const std::uint32_t width = in.number("width");
  const std::uint32_t height = in.number("height");
  const std::uint32_t maxval = in.number("maxval");
  if (width == 0 || height == 0) Reader::fail("a size of " + std::to_string(width) + "x" + std::to_string(height));
  if (width > static_cast<std::uint32_t>(kMaxImageSide) || height > static_cast<std::uint32_t>(kMaxImageSide)) {
    throw std::runtime_error(std::to_string(width) + "x" + std::to_string(height) + " pixels is more than the limit of " +
                             std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide));
  }
  if (maxval == 0 || maxval > 65535) Reader::fail("maxval " + std::to_string(maxval) + " (allowed: 1-65535)");
  const bool sixteen = maxval > 255;
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_MAKETYPE(sixteen ? CV_16U : CV_8U, channels));
  const std::size_t samples = std::size_t{width} * channels;
  for (int y = 0; y < image.rows; ++y) {
    if (binary && !sixteen) {
      std::memcpy(image.ptr(y), in.take(samples), samples);
    } else if (binary) {
      const std::uint8_t* from = in.take(samples * 2);
      auto* row = image.ptr<std::uint16_t>(y);
      for (std::size_t i = 0; i < samples; ++i) row[i] = static_cast<std::uint16_t>(from[2 * i] << 8 | from[2 * i + 1]);
    } else {
      for (std::size_t i = 0; i < samples; ++i) {
        const std::uint32_t value = std::min(in.number("sample"), maxval);
        if (sixteen) {
          image.ptr<std::uint16_t>(y)[i] = static_cast<std::uint16_t>(value);
        } else {
          image.ptr<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(value * 255 / maxval);
        }
      }
    }
    if (channels == 3) {  // stored as RGB, held as BGR
      if (sixteen) {
        auto* row = image.ptr<std::uint16_t>(y);
        for (std::uint32_t x = 0; x < width; ++x) std::swap(row[3 * x], row[3 * x + 2]);
      } else {
        auto* row = image.ptr<std::uint8_t>(y);
        for (std::uint32_t x = 0; x < width; ++x) std::swap(row[3 * x], row[3 * x + 2]);
      }
    }
  }
  return image;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
