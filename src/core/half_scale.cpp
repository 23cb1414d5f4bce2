#include "core/half_scale.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace lidar_sgm {
namespace {

template <typename Pixel>
void downscaleHalfImpl(ImageView<const Pixel> in, Image<Pixel>& out) {
  out.resize(halfSize(in.width), halfSize(in.height));
  for (int y = 0; y < out.height(); ++y) {
    const Pixel* row0 = in.row(2 * y);
    const Pixel* row1 = in.row(std::min(2 * y + 1, in.height - 1));
    for (int x = 0; x < out.width(); ++x) {
      const int x0 = 2 * x;
      const int x1 = std::min(x0 + 1, in.width - 1);
      const std::uint32_t sum = std::uint32_t{row0[x0]} + row0[x1] + row1[x0] + row1[x1];
      out(x, y) = static_cast<Pixel>((sum + 2) >> 2);
    }
  }
}

}  // namespace

void downscaleHalf(ImageView<const std::uint8_t> in, Image<std::uint8_t>& out) { downscaleHalfImpl(in, out); }
void downscaleHalf(ImageView<const std::uint16_t> in, Image<std::uint16_t>& out) { downscaleHalfImpl(in, out); }

GrayImageView downscaleHalf(const GrayImageView& in, Image<std::uint8_t>& buffer8, Image<std::uint16_t>& buffer16) {
  if (in.empty()) return {};
  if (!in.gray8.empty()) {
    downscaleHalf(in.gray8, buffer8);
    return GrayImageView(std::as_const(buffer8).view());
  }
  downscaleHalf(in.gray16, buffer16);
  return GrayImageView(std::as_const(buffer16).view());
}

void halveLidarPoints(const LidarPoints& points, std::vector<LidarSample>& samples, LidarPoints& half) {
  // The points in their stored order (ascending pixel, then as given): the order of a walk over
  // the pixels, without reading the offsets of the many pixels that hold none.
  const std::vector<int>& pixels = points.pointPixels();
  const std::vector<int>& disparities = points.disparities16();
  const int width = points.width();
  samples.resize(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const int x = pixels[i] % width;
    const int y = pixels[i] / width;
    samples[i] = {x / 2, y / 2, (disparities[i] + 1) / 2};
  }
  half.assign(halfSize(points.width()), halfSize(points.height()), samples);
}

LidarPoints halveLidarPoints(const LidarPoints& points) {
  std::vector<LidarSample> samples;
  LidarPoints half;
  halveLidarPoints(points, samples, half);
  return half;
}

// Rows 2k and 2k + 1 of `full` are the same: each half row is widened once and copied once.
void upscaleDisparity(ImageView<const std::int16_t> half, ImageView<std::int16_t> full) {
  for (int y = 0; y < full.height; ++y) {
    std::int16_t* dst = full.row(y);
    if (y % 2 == 1) {
      std::copy(full.row(y - 1), full.row(y - 1) + full.width, dst);
      continue;
    }
    const std::int16_t* src = half.row(y / 2);
    for (int x = 0; x < full.width; ++x) {
      const std::int16_t d = src[x / 2];
      dst[x] = d == kInvalidDisparity ? kInvalidDisparity : static_cast<std::int16_t>(2 * d);
    }
  }
}

void upscaleMask(ImageView<const std::uint8_t> half, ImageView<std::uint8_t> full) {
  for (int y = 0; y < full.height; ++y) {
    std::uint8_t* dst = full.row(y);
    if (y % 2 == 1) {
      std::copy(full.row(y - 1), full.row(y - 1) + full.width, dst);
      continue;
    }
    const std::uint8_t* src = half.row(y / 2);
    for (int x = 0; x < full.width; ++x) dst[x] = src[x / 2];
  }
}

}  // namespace lidar_sgm
