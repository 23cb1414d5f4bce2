// Open3D images <-> lidar_sgm images. Open3D keeps every image as bytes (data_) with its
// channels interleaved and 16-bit values in the machine's byte order, as cv::Mat does; its own
// Image::PointerAt<T> reads them through a cast, as the views here do.
#include "lidar_sgm/open3d/image_conversion.hpp"

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace {

using Open3dImage = ::open3d::geometry::Image;

std::string describe(const Open3dImage& image) {
  return std::to_string(image.width_) + "x" + std::to_string(image.height_) + ", " +
         std::to_string(image.num_of_channels_) + " channel(s) of " + std::to_string(image.bytes_per_channel_) +
         " byte(s)";
}

/// Throws unless `image` is non-empty, 1/3/4 channels of 1 or 2 bytes, and data_ holds exactly
/// its pixels (Open3D does not check that its public members agree).
void checkFormat(const Open3dImage& image, const char* what) {
  if (image.width_ <= 0 || image.height_ <= 0) {
    throw std::invalid_argument(std::string(what) + ": the Open3D image is empty");
  }
  const int c = image.num_of_channels_;
  const int b = image.bytes_per_channel_;
  if ((c != 1 && c != 3 && c != 4) || (b != 1 && b != 2)) {
    throw std::invalid_argument(std::string(what) + ": expected an Open3D image of 1, 3 or 4 channels of 8- or 16-bit " +
                                "unsigned values, got " + describe(image));
  }
  const std::size_t expected = static_cast<std::size_t>(image.width_) * image.height_ * c * b;
  if (image.data_.size() != expected) {
    throw std::invalid_argument(std::string(what) + ": the Open3D image (" + describe(image) + ") holds " +
                                std::to_string(image.data_.size()) + " bytes, not " + std::to_string(expected));
  }
}

template <typename T>
const T* pixels(const Open3dImage& image) {
  return reinterpret_cast<const T*>(image.data_.data());
}

// BT.601 gray in OpenCV's fixed point, so that an RGB pair read by Open3D matches as the same
// pair read by the tools (io::toGray, cv::cvtColor): 8 bit with 15 fractional bits (exactly
// cvtColor's), 16 bit with OpenCV's documented 14 (its vector code differs by up to 2 levels).
std::uint8_t grayOf(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return static_cast<std::uint8_t>((r * 9798 + g * 19235 + b * 3735 + (1 << 14)) >> 15);
}
std::uint16_t grayOf(std::uint16_t r, std::uint16_t g, std::uint16_t b) {
  return static_cast<std::uint16_t>((r * 4899u + g * 9617u + b * 1868u + (1u << 13)) >> 14);
}

template <typename T>
void toGray(const Open3dImage& image, Image<T>& gray) {
  gray.resize(image.width_, image.height_);
  const T* src = pixels<T>(image);
  const std::size_t channels = static_cast<std::size_t>(image.num_of_channels_);
  const std::size_t count = static_cast<std::size_t>(image.width_) * image.height_;
  T* dst = gray.data();
  if (channels == 1) {
    std::memcpy(dst, src, count * sizeof(T));
    return;
  }
  for (std::size_t i = 0; i < count; ++i, src += channels) dst[i] = grayOf(src[0], src[1], src[2]);
}

std::uint8_t to8Bit(std::uint8_t v) { return v; }
// io::toColor's convertTo(CV_8U, 1/257): v / 257 rounded; never exactly half way (v is an integer).
std::uint8_t to8Bit(std::uint16_t v) { return static_cast<std::uint8_t>((v + 128u) / 257u); }

template <typename T>
void toRgb(const Open3dImage& image, Image<Rgb8>& color) {
  const T* src = pixels<T>(image);
  const std::size_t channels = static_cast<std::size_t>(image.num_of_channels_);
  const std::size_t count = static_cast<std::size_t>(image.width_) * image.height_;
  Rgb8* dst = color.data();
  for (std::size_t i = 0; i < count; ++i, src += channels) {
    if (channels == 1) {
      const std::uint8_t v = to8Bit(src[0]);
      dst[i] = Rgb8{v, v, v};
    } else {
      dst[i] = Rgb8{to8Bit(src[0]), to8Bit(src[1]), to8Bit(src[2])};
    }
  }
}

template <typename T>
std::shared_ptr<Open3dImage> copyToOpen3d(ImageView<const T> view, int channels, int bytesPerChannel) {
  if (view.empty()) throw std::invalid_argument("toOpen3dImage: the image is empty");
  auto image = std::make_shared<Open3dImage>();
  image->Prepare(view.width, view.height, channels, bytesPerChannel);
  const std::size_t rowBytes = static_cast<std::size_t>(view.width) * sizeof(T);
  for (int y = 0; y < view.height; ++y) {
    std::memcpy(image->data_.data() + static_cast<std::size_t>(y) * rowBytes, view.row(y), rowBytes);
  }
  return image;
}

}  // namespace

GrayImageView grayView(const Open3dImage& image) {
  checkFormat(image, "grayView");
  if (image.num_of_channels_ != 1) {
    throw std::invalid_argument("grayView: expected a 1-channel Open3D image, got " + describe(image) +
                                " (Open3dGray converts color)");
  }
  if (image.bytes_per_channel_ == 1) {
    return ImageView<const std::uint8_t>(pixels<std::uint8_t>(image), image.width_, image.height_);
  }
  return ImageView<const std::uint16_t>(pixels<std::uint16_t>(image), image.width_, image.height_);
}

Open3dGray::Open3dGray(const Open3dImage& image) {
  checkFormat(image, "Open3dGray");
  if (image.bytes_per_channel_ == 1) {
    toGray(image, gray8_);
  } else {
    toGray(image, gray16_);
  }
}

GrayImageView Open3dGray::view() const {
  if (!gray8_.empty()) return gray8_.view();
  return gray16_.view();
}

Image<Rgb8> toRgb8(const Open3dImage& image) {
  checkFormat(image, "toRgb8");
  Image<Rgb8> color(image.width_, image.height_);
  if (image.bytes_per_channel_ == 1) {
    toRgb<std::uint8_t>(image, color);
  } else {
    toRgb<std::uint16_t>(image, color);
  }
  return color;
}

std::shared_ptr<Open3dImage> toOpen3dImage(ImageView<const std::uint8_t> image) {
  return copyToOpen3d(image, 1, 1);
}
std::shared_ptr<Open3dImage> toOpen3dImage(ImageView<const std::uint16_t> image) {
  return copyToOpen3d(image, 1, 2);
}
std::shared_ptr<Open3dImage> toOpen3dImage(ImageView<const Rgb8> image) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be three packed bytes, as Open3D's RGB pixels");
  return copyToOpen3d(image, 3, 1);
}
std::shared_ptr<Open3dImage> toOpen3dImage(ImageView<const float> image) {
  return copyToOpen3d(image, 1, 4);
}

}  // namespace lidar_sgm
