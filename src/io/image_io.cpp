#include "lidar_sgm/io/image_io.hpp"

#include "lidar_sgm/geometry/calibration.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <opencv2/imgcodecs.hpp>  // the IMWRITE_* names only: the codecs are ours (png_codec.hpp says why)
#include <opencv2/imgproc.hpp>

#include "image_header.hpp"
#include "jpeg_decoder.hpp"
#include "png_codec.hpp"
#include "pnm_decoder.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include <unistd.h>

static_assert(lidar_sgm::io::kMaxImageSide == lidar_sgm::geometry::StereoCalibration::kMaxImageSide,
              "one image size limit for images and calibrations");

namespace lidar_sgm {
namespace io {
namespace fs = std::filesystem;
namespace {

// A PNG's size is in its first chunk (IHDR): checked before decoding, since the decoder allocates
// the whole image first (a 1 MB PNG of 30000x30000 would ask for 8.6 GB).
void requirePngSizeWithinLimit(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const detail::PngHeader png = detail::parsePngHeader(bytes.data(), bytes.size());
  if (!png.ihdr) return;  // not a PNG, or a broken one: the decoder refuses it
  const auto limit = static_cast<std::uint32_t>(kMaxImageSide);
  if (png.width > limit || png.height > limit) detail::failImageTooLarge(path, png.width, png.height);
}

enum class ImageFormat { Png, Jpeg, Pnm };

// The formats a rig's images come in: PNG, JPEG and binary or ASCII PGM/PPM, each known by the
// signature at byte 0 (not by the file's name).
ImageFormat requireImageSignature(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const unsigned char* head = bytes.data();
  const std::size_t got = bytes.size();
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (got >= 8 && std::memcmp(head, kPng, 8) == 0) return ImageFormat::Png;
  if (got >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return ImageFormat::Jpeg;
  if (got >= 3 && head[0] == 'P' && (head[1] == '2' || head[1] == '3' || head[1] == '5' || head[1] == '6') &&
      std::isspace(head[2]) != 0) {
    return ImageFormat::Pnm;
  }
  throw std::runtime_error("cannot read image '" + path +
                           "': not a PNG, JPEG or PGM/PPM file (its first bytes are none of their signatures)");
}

std::vector<std::uint8_t> readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error("cannot read image '" + path + "': cannot open it");
  const std::streamoff size = in.tellg();
  if (size < 0) throw std::runtime_error("cannot read image '" + path + "': cannot tell its size");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw std::runtime_error("cannot read image '" + path + "': a read error");
  }
  return bytes;
}

cv::Mat readAny(const std::string& path) {
  const std::string unreadable = unreadableFileReason(path);
  if (!unreadable.empty()) throw std::runtime_error("cannot read image '" + path + "': " + unreadable);
  // Read once; the signature and a PNG's size are checked on these bytes before decoding.
  const std::vector<std::uint8_t> bytes = readWholeFile(path);
  const ImageFormat format = requireImageSignature(path, bytes);
  requirePngSizeWithinLimit(path, bytes);
  cv::Mat image;
  try {
    switch (format) {
      case ImageFormat::Png: image = detail::decodePng(bytes.data(), bytes.size()); break;
      case ImageFormat::Jpeg: image = detail::decodeJpeg(bytes.data(), bytes.size()); break;
      case ImageFormat::Pnm: image = detail::decodePnm(bytes.data(), bytes.size()); break;
    }
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot read image '" + path + "': " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot read image '" + path + "': not a readable image file (" + e.what() + ")");
  }
  if (image.empty()) throw std::runtime_error("cannot read image '" + path + "': not a readable image file");
  if (image.cols > kMaxImageSide || image.rows > kMaxImageSide) {
    detail::failImageTooLarge(path, static_cast<std::uint64_t>(image.cols), static_cast<std::uint64_t>(image.rows));
  }
  return image;
}

cv::Mat readSixteenBitGray(const std::string& path, const char* what) {
  cv::Mat image = readAny(path);
  if (image.type() != CV_16UC1) {
    throw std::runtime_error("'" + path + "' is not a " + what +
                             " PNG: expected a 16-bit single-channel image");
  }
  return image;
}

}  // namespace

cv::Mat readImage(const std::string& path) {
  cv::Mat image = readAny(path);
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw std::runtime_error("cannot use image '" + path + "': only 8- and 16-bit images are supported");
  }
  if (image.channels() != 1 && image.channels() != 3 && image.channels() != 4) {
    throw std::runtime_error("cannot use image '" + path + "': expected 1, 3 or 4 channels, it has " +
                             std::to_string(image.channels()));
  }
  return image;
}

cv::Mat toGray(const cv::Mat& image) {
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw std::invalid_argument("toGray: expected an 8- or 16-bit image, got depth " + std::to_string(image.depth()));
  }
  if (image.channels() == 1) return image;
  if (image.channels() != 3 && image.channels() != 4) {
    throw std::invalid_argument("toGray: expected 1, 3 or 4 channels, got " + std::to_string(image.channels()));
  }
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

cv::Mat toColor(const cv::Mat& image) {
  cv::Mat color = image;
  if (color.depth() == CV_16U) color.convertTo(color, CV_8U, 1.0 / 257.0);
  if (color.channels() == 1) cv::cvtColor(color, color, cv::COLOR_GRAY2BGR);
  if (color.channels() == 4) cv::cvtColor(color, color, cv::COLOR_BGRA2BGR);
  return color;
}

cv::Mat readGrayImage(const std::string& path) { return toGray(readImage(path)); }

cv::Mat readColorImage(const std::string& path) { return toColor(readImage(path)); }

GrayImageView grayView(const cv::Mat& gray) {
  if (gray.type() == CV_8UC1) {
    return ImageView<const std::uint8_t>(gray.ptr<std::uint8_t>(), gray.cols, gray.rows,
                                         static_cast<std::ptrdiff_t>(gray.step1()));
  }
  if (gray.type() == CV_16UC1) {
    return ImageView<const std::uint16_t>(gray.ptr<std::uint16_t>(), gray.cols, gray.rows,
                                          static_cast<std::ptrdiff_t>(gray.step1()));
  }
  throw std::invalid_argument("grayView: expected an 8- or 16-bit single-channel image");
}

Image<std::int16_t> readKittiDisparity(const std::string& path) {
  const cv::Mat png = readSixteenBitGray(path, "KITTI disparity");
  Image<std::int16_t> disparity(png.cols, png.rows, kInvalidDisparity);
  for (int y = 0; y < png.rows; ++y) {
    for (int x = 0; x < png.cols; ++x) {
      const int v = png.at<std::uint16_t>(y, x);
      // value/256 px -> x16: divide by 16, rounded; 0 means "no value" in the format.
      if (v != 0) disparity(x, y) = static_cast<std::int16_t>((v + 8) / 16);
    }
  }
  return disparity;
}

Image<float> readKittiDisparityFloat(const std::string& path) {
  const cv::Mat png = readSixteenBitGray(path, "KITTI disparity");
  Image<float> disparity(png.cols, png.rows, 0.0f);
  for (int y = 0; y < png.rows; ++y) {
    for (int x = 0; x < png.cols; ++x) disparity(x, y) = png.at<std::uint16_t>(y, x) / 256.0f;
  }
  return disparity;
}

Image<std::int16_t> readKittiDepthAsDisparity(const std::string& path, double focalBaseline) {
  if (!(focalBaseline > 0.0) || !std::isfinite(focalBaseline)) {
    throw std::invalid_argument("focal length * baseline must be a positive number of px*m, got " +
                                std::to_string(focalBaseline));
  }
  const cv::Mat png = readSixteenBitGray(path, "KITTI depth");
  Image<std::int16_t> disparity(png.cols, png.rows, kInvalidDisparity);
  for (int y = 0; y < png.rows; ++y) {
    for (int x = 0; x < png.cols; ++x) {
      const int v = png.at<std::uint16_t>(y, x);
      if (v == 0) continue;
      const double depth = v / 256.0;
      const long d16 = std::lround(focalBaseline / depth * kDisparityScale);  // Eq. 3
      if (d16 > 0 && d16 <= 32767) disparity(x, y) = static_cast<std::int16_t>(d16);
    }
  }
  return disparity;
}

cv::Mat toKittiDisparity(ImageView<const std::int16_t> disparity16) {
  cv::Mat png(disparity16.height, disparity16.width, CV_16UC1);
  for (int y = 0; y < disparity16.height; ++y) {
    for (int x = 0; x < disparity16.width; ++x) {
      const int d = disparity16(x, y);
      png.at<std::uint16_t>(y, x) =
          static_cast<std::uint16_t>(d == kInvalidDisparity || d <= 0 ? 0 : d * (256 / kDisparityScale));
    }
  }
  return png;
}

cv::Mat toKittiDepth(ImageView<const float> depth) {
  cv::Mat png(depth.height, depth.width, CV_16UC1);
  for (int y = 0; y < depth.height; ++y) {
    for (int x = 0; x < depth.width; ++x) {
      const double scaled = std::round(static_cast<double>(depth(x, y)) * 256.0);
      const bool representable = scaled >= 1.0 && scaled <= 65535.0;  // false for NaN too
      png.at<std::uint16_t>(y, x) = representable ? static_cast<std::uint16_t>(scaled) : 0;
    }
  }
  return png;
}

cv::Mat toConfidencePng(ImageView<const std::uint8_t> confidence) {
  if (confidence.empty()) throw std::invalid_argument("toConfidencePng: there is no confidence (it was turned off)");
  cv::Mat png(confidence.height, confidence.width, CV_8UC1);
  for (int y = 0; y < confidence.height; ++y) {
    std::copy(confidence.row(y), confidence.row(y) + confidence.width, png.ptr<std::uint8_t>(y));
  }
  return png;
}

cv::Mat colorizeDisparity(ImageView<const std::int16_t> disparity16, double maxDisparity) {
  cv::Mat scaled(disparity16.height, disparity16.width, CV_8UC1);
  cv::Mat invalid(disparity16.height, disparity16.width, CV_8UC1, cv::Scalar(0));
  const double scale = 255.0 / (std::max(maxDisparity, 1.0) * kDisparityScale);
  for (int y = 0; y < disparity16.height; ++y) {
    for (int x = 0; x < disparity16.width; ++x) {
      const int d = disparity16(x, y);
      if (d == kInvalidDisparity) invalid.at<std::uint8_t>(y, x) = 255;
      scaled.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(d == kInvalidDisparity ? 0 : d * scale);
    }
  }
  cv::Mat color;
  cv::applyColorMap(scaled, color, cv::COLORMAP_TURBO);
  color.setTo(cv::Scalar(0, 0, 0), invalid);
  return color;
}

cv::Mat quantiseColors(const cv::Mat& image, int levels) {
  if (levels < 2 || levels > 256) {
    throw std::invalid_argument("quantiseColors: levels must be 2..256, got " + std::to_string(levels));
  }
  if (image.depth() != CV_8U) throw std::invalid_argument("quantiseColors: expected an 8-bit image");
  cv::Mat table(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) {
    const double step = std::round(i * (levels - 1) / 255.0);  // the nearest of the levels
    table.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(std::lround(step * 255.0 / (levels - 1)));
  }
  cv::Mat quantised;
  cv::LUT(image, table, quantised);
  return quantised;
}

void writeImageAtomically(const std::string& path, const cv::Mat& image) { writeImageAtomically(path, image, {}); }

void writeImageAtomically(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  // Encoded in memory, then written through AtomicFile: every write is checked, so a full disk
  // cannot leave a truncated PNG.
  if (lowerExtension(path) != ".png") {
    throw std::runtime_error("cannot write '" + path + "': images are written as PNG (a .png file)");
  }
  if (params.size() % 2 != 0) throw std::invalid_argument("writeImageAtomically: parameters come in name, value pairs");
  int compression = -1;
  for (std::size_t i = 0; i < params.size(); i += 2) {
    if (params[i] != cv::IMWRITE_PNG_COMPRESSION) {
      throw std::invalid_argument("writeImageAtomically: only cv::IMWRITE_PNG_COMPRESSION is taken, got parameter " +
                                  std::to_string(params[i]));
    }
    compression = params[i + 1];
    if (compression < 0 || compression > 9) {
      throw std::invalid_argument("writeImageAtomically: PNG compression must be 0-9, got " + std::to_string(compression));
    }
  }
  std::vector<std::uint8_t> encoded;
  try {
    encoded = detail::encodePng(image, compression);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  writeFileAtomically(path, encoded.data(), encoded.size());
}

}  // namespace io
}  // namespace lidar_sgm
