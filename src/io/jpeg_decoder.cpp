// JPEG through libjpeg(-turbo), with OpenCV's output layout (jpeg_decoder.hpp). libjpeg reports
// errors by its error_exit, which longjmps here: the setjmp sits in a function whose locals are
// plain data.
#include "jpeg_decoder.hpp"

#include <csetjmp>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <jpeglib.h>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

struct ErrorManager {
  jpeg_error_mgr base;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "";
};

[[noreturn]] void onError(j_common_ptr info) {
  auto* error = reinterpret_cast<ErrorManager*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->jump, 1);
}

void onMessage(j_common_ptr, int) {}  // warnings (a corrupt but decodable stream) stay quiet, as in OpenCV

struct Decompressor {
  ErrorManager error;
  jpeg_decompress_struct info{};
  Decompressor() {
    info.err = jpeg_std_error(&error.base);
    error.base.error_exit = onError;
    error.base.emit_message = onMessage;
    jpeg_create_decompress(&info);
  }
  ~Decompressor() { jpeg_destroy_decompress(&info); }
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;
};

bool readHeader(Decompressor& d, const std::uint8_t* bytes, std::size_t size) {
  if (setjmp(d.error.jump) != 0) return false;
  jpeg_mem_src(&d.info, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&d.info, TRUE);
  return true;
}

// OpenCV's JpegDecoder::readData for IMREAD_UNCHANGED: gray stays gray, color comes out as BGR.
bool readPixels(Decompressor& d, bool color, JSAMPARRAY rows, int height) {
  if (setjmp(d.error.jump) != 0) return false;
  d.info.out_color_space = color ? JCS_EXT_BGR : JCS_GRAYSCALE;
  d.info.out_color_components = color ? 3 : 1;
  jpeg_start_decompress(&d.info);
  while (static_cast<int>(d.info.output_scanline) < height) {
    jpeg_read_scanlines(&d.info, rows + d.info.output_scanline, static_cast<JDIMENSION>(height) - d.info.output_scanline);
  }
  jpeg_finish_decompress(&d.info);
  return true;
}

}  // namespace

cv::Mat decodeJpeg(const std::uint8_t* bytes, std::size_t size) {
  Decompressor d;
  if (!readHeader(d, bytes, size)) throw std::runtime_error(d.error.message);
  if (d.info.num_components == 4) throw std::runtime_error("a CMYK JPEG (only gray and color JPEGs are read)");
  const bool color = d.info.num_components > 1;
  cv::Mat image(static_cast<int>(d.info.image_height), static_cast<int>(d.info.image_width), color ? CV_8UC3 : CV_8UC1);
  std::vector<JSAMPROW> rows(static_cast<std::size_t>(image.rows));
  for (int y = 0; y < image.rows; ++y) rows[static_cast<std::size_t>(y)] = image.ptr<JSAMPLE>(y);
  if (!readPixels(d, color, rows.data(), image.rows)) throw std::runtime_error(d.error.message);
  return image;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
