#include "lidar_sgm/synth/encoding.hpp"

#include <cmath>
#include <cstring>

namespace lidar_sgm {
namespace synth {
namespace {

Image<std::uint16_t> encodeTimes256(ImageView<const float> values) {
  Image<std::uint16_t> out(values.width, values.height, 0);
  for (int y = 0; y < values.height; ++y) {
    for (int x = 0; x < values.width; ++x) {
      const double scaled = std::round(static_cast<double>(values(x, y)) * 256.0);
      if (scaled >= 1.0 && scaled <= 65535.0) out(x, y) = static_cast<std::uint16_t>(scaled);
    }
  }
  return out;
}

void appendLittleEndian(std::string& bytes, float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((bits >> (8 * i)) & 0xFFu));
}

}  // namespace

Image<std::uint16_t> encodeKittiDisparity(ImageView<const float> disparity) { return encodeTimes256(disparity); }

Image<std::uint16_t> encodeKittiDepth(ImageView<const float> depth) { return encodeTimes256(depth); }

std::string velodyneBytes(const std::vector<LidarPoint>& points) {
  std::string bytes;
  bytes.reserve(points.size() * 16);
  for (const LidarPoint& p : points) {
    appendLittleEndian(bytes, p.x);
    appendLittleEndian(bytes, p.y);
    appendLittleEndian(bytes, p.z);
    appendLittleEndian(bytes, p.intensity);
  }
  return bytes;
}

Image<std::uint8_t> toGray(const Image<Rgb8>& color) {
  Image<std::uint8_t> gray(color.width(), color.height());
  for (int y = 0; y < color.height(); ++y) {
    for (int x = 0; x < color.width(); ++x) {
      const Rgb8& p = color(x, y);
      // 0.299 R + 0.587 G + 0.114 B in 14-bit fixed point, rounded.
      gray(x, y) = static_cast<std::uint8_t>((p.r * 4899 + p.g * 9617 + p.b * 1868 + 8192) >> 14);
    }
  }
  return gray;
}

}  // namespace synth
}  // namespace lidar_sgm
