// PNG through libpng with OpenCV's transforms and encoder settings (png_codec.hpp says why).
// libpng reports errors by longjmp: each setjmp sits in a function whose locals are plain data,
// and everything with a destructor lives in its caller.
#include "png_codec.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <png.h>
#include <zlib.h>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

struct PngError {
  char message[256] = "";
};

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof error->message, "%s", message);
  png_longjmp(png, 1);
}

// A rig's PNGs often carry ancillary chunks libpng warns about (an sRGB profile it knows as
// inexact): not errors, and not the tools' business to print.
void onWarning(png_structp, png_const_charp) {}

bool littleEndian() {
  const std::uint16_t one = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

struct MemoryReader {
  const std::uint8_t* bytes = nullptr;
  std::size_t size = 0;
  std::size_t at = 0;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t count) {
  auto* in = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (count > in->size - in->at) png_error(png, "the file ends inside the image");
  std::memcpy(out, in->bytes + in->at, count);
  in->at += count;
}

struct ReadStructs {
  PngError error;
  png_structp png = nullptr;
  png_infop info = nullptr;
  ReadStructs() {
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
    if (png != nullptr) info = png_create_info_struct(png);
    if (png == nullptr || info == nullptr) throw std::runtime_error("libpng could not start (out of memory)");
  }
  ~ReadStructs() { png_destroy_read_struct(&png, &info, nullptr); }
  ReadStructs(const ReadStructs&) = delete;
  ReadStructs& operator=(const ReadStructs&) = delete;
};

struct Header {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bitDepth = 0;
  int colorType = 0;
  int transparent = 0;  // tRNS entries
};

bool readHeader(ReadStructs& s, MemoryReader* reader, Header* header) {
  if (setjmp(png_jmpbuf(s.png)) != 0) return false;
  png_set_read_fn(s.png, reader, readFromMemory);
  png_read_info(s.png, s.info);
  png_get_IHDR(s.png, s.info, &header->width, &header->height, &header->bitDepth, &header->colorType, nullptr,
               nullptr, nullptr);
  png_bytep trans = nullptr;
  png_color_16p values = nullptr;
  if (png_get_tRNS(s.png, s.info, &trans, &header->transparent, &values) == 0) header->transparent = 0;
  return true;
}

// OpenCV's PngDecoder::readData transforms for IMREAD_UNCHANGED (the channels decided from the header).
bool readPixels(ReadStructs& s, const Header& header, int channels, std::size_t rowBytes, png_bytepp rows) {
  if (setjmp(png_jmpbuf(s.png)) != 0) return false;
  if (header.bitDepth == 16 && littleEndian()) png_set_swap(s.png);
  if (channels < 4) {
    png_set_strip_alpha(s.png);
  } else {
    png_set_tRNS_to_alpha(s.png);
  }
  if (header.colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(s.png);
  const bool colorFile = (header.colorType & PNG_COLOR_MASK_COLOR) != 0;
  if (!colorFile && header.bitDepth < 8) png_set_expand_gray_1_2_4_to_8(s.png);
  if (colorFile && channels > 1) {
    png_set_bgr(s.png);
  } else if (channels > 1) {
    png_set_gray_to_rgb(s.png);
  }
  png_set_interlace_handling(s.png);
  png_read_update_info(s.png, s.info);
  if (png_get_rowbytes(s.png, s.info) != rowBytes) png_error(s.png, "unexpected row size after the transforms");
  png_read_image(s.png, rows);
  png_read_end(s.png, nullptr);
  return true;
}

struct WriteStructs {
  PngError error;
  png_structp png = nullptr;
  png_infop info = nullptr;
  WriteStructs() {
    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
    if (png != nullptr) info = png_create_info_struct(png);
    if (png == nullptr || info == nullptr) throw std::runtime_error("libpng could not start (out of memory)");
  }
  ~WriteStructs() { png_destroy_write_struct(&png, &info); }
  WriteStructs(const WriteStructs&) = delete;
  WriteStructs& operator=(const WriteStructs&) = delete;
};

void writeToMemory(png_structp png, png_bytep data, png_size_t count) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  bool failed = false;
  try {
    out->insert(out->end(), data, data + count);
  } catch (...) {
    failed = true;
  }
  if (failed) png_error(png, "out of memory");
}

void flushNothing(png_structp) {}

// OpenCV's PngEncoder::write: without a level, speed first (level 1, SUB filter, RLE).
bool writePixels(WriteStructs& s, png_uint_32 width, png_uint_32 height, int bitDepth, int colorType, int compression,
                 std::vector<std::uint8_t>* out, png_bytepp rows) {
  if (setjmp(png_jmpbuf(s.png)) != 0) return false;
  png_set_write_fn(s.png, out, writeToMemory, flushNothing);
  int strategy = Z_DEFAULT_STRATEGY;
  if (compression >= 0) {
    png_set_compression_level(s.png, compression);
  } else {
    png_set_filter(s.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_compression_level(s.png, Z_BEST_SPEED);
    strategy = Z_RLE;
  }
  png_set_compression_strategy(s.png, strategy);
  png_set_IHDR(s.png, s.info, width, height, bitDepth, colorType, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(s.png, s.info);
  png_set_bgr(s.png);
  if (littleEndian()) png_set_swap(s.png);
  png_write_image(s.png, rows);
  png_write_end(s.png, s.info);
  return true;
}

}  // namespace

cv::Mat decodePng(const std::uint8_t* bytes, std::size_t size) {
  ReadStructs s;
  MemoryReader reader{bytes, size, 0};
  Header header;
  if (!readHeader(s, &reader, &header)) throw std::runtime_error(s.error.message);
  if (header.width == 0 || header.height == 0 || header.width > static_cast<png_uint_32>(1 << 30) / 8 ||
      header.height > static_cast<png_uint_32>(1 << 30)) {
    throw std::runtime_error("an image of " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                             " pixels");
  }
  // OpenCV's PngDecoder::readHeader: the channels the file's color type gives.
  int channels = 1;
  switch (header.colorType) {
    case PNG_COLOR_TYPE_RGB:
    case PNG_COLOR_TYPE_PALETTE: channels = header.transparent > 0 ? 4 : 3; break;
    case PNG_COLOR_TYPE_GRAY_ALPHA:
    case PNG_COLOR_TYPE_RGB_ALPHA: channels = 4; break;
    default: channels = 1;
  }
  cv::Mat image(static_cast<int>(header.height), static_cast<int>(header.width),
                CV_MAKETYPE(header.bitDepth == 16 ? CV_16U : CV_8U, channels));
  std::vector<png_bytep> rows(header.height);
  for (png_uint_32 y = 0; y < header.height; ++y) rows[y] = image.ptr<png_byte>(static_cast<int>(y));
  const std::size_t rowBytes = static_cast<std::size_t>(image.cols) * image.elemSize();
  if (!readPixels(s, header, channels, rowBytes, rows.data())) throw std::runtime_error(s.error.message);
  return image;
}

std::vector<std::uint8_t> encodePng(const cv::Mat& image, int compression) {
  if (image.empty()) throw std::invalid_argument("cannot encode an empty image as PNG");
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw std::invalid_argument("PNG holds 8- or 16-bit images, got depth " + std::to_string(image.depth()));
  }
  const int channels = image.channels();
  if (channels != 1 && channels != 3 && channels != 4) {
    throw std::invalid_argument("PNG holds 1, 3 or 4 channels, got " + std::to_string(channels));
  }
  if (compression < -1 || compression > 9) {
    throw std::invalid_argument("PNG compression must be 0-9 (or -1 for the default), got " +
                                std::to_string(compression));
  }
  const int colorType = channels == 1 ? PNG_COLOR_TYPE_GRAY : channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA;
  // libpng's transforms read the rows without writing them; its API takes them as non-const.
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.rows));
  for (int y = 0; y < image.rows; ++y) rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.ptr<png_byte>(y));
  std::vector<std::uint8_t> out;
  out.reserve(static_cast<std::size_t>(image.cols) * image.rows * image.elemSize() / 2 + 1024);
  WriteStructs s;
  if (!writePixels(s, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows),
                   image.depth() == CV_8U ? 8 : 16, colorType, compression, &out, rows.data())) {
    throw std::runtime_error(std::string("libpng: ") + s.error.message);
  }
  return out;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
