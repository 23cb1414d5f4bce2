#pragma once
// 7x7 zero-mean SAD patch comparisons between the left and right images, for the checks that
// ask the stereo pair a question at single pixels (the pair's orientation, a LiDAR point's
// consistency) without running the matcher.

#include <cstdint>
#include <cstdlib>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace patch {

constexpr int kRadius = 3;  ///< 7x7 patches
constexpr int kArea = (2 * kRadius + 1) * (2 * kRadius + 1);

/// One gray image of either depth, read as int.
struct Gray {
  ImageView<const std::uint8_t> g8;
  ImageView<const std::uint16_t> g16;
  explicit Gray(const GrayImageView& v) : g8(v.gray8), g16(v.gray16) {}
  int at(int x, int y) const { return g8.empty() ? g16(x, y) : g8(x, y); }
  int width() const { return g8.empty() ? g16.width : g8.width; }
  int height() const { return g8.empty() ? g16.height : g8.height; }
  /// A patch with less mean deviation than this is textureless: 2 gray levels at 8 bit.
  double flatness() const { return g8.empty() ? 2.0 * 257.0 : 2.0; }
};

/// Mean of the 7x7 patch around (x, y).
inline double patchMean(const Gray& image, int x, int y) {
  long sum = 0;
  for (int j = -kRadius; j <= kRadius; ++j) {
    for (int i = -kRadius; i <= kRadius; ++i) sum += image.at(x + i, y + j);
  }
  return static_cast<double>(sum) / kArea;
}

/// Mean absolute deviation of the patch around (x, y) from its `mean`: its texture.
inline double patchTexture(const Gray& image, int x, int y, double mean) {
  double sum = 0.0;
  for (int j = -kRadius; j <= kRadius; ++j) {
    for (int i = -kRadius; i <= kRadius; ++i) sum += std::abs(image.at(x + i, y + j) - mean);
  }
  return sum / kArea;
}

/// Zero-mean SAD of the left patch at (x, y), of mean `ml`, and the right one at (xr, y): robust
/// to the gain and offset two cameras' exposures differ by.
inline double zsad(const Gray& left, double ml, const Gray& right, int x, int xr, int y) {
  const double mr = patchMean(right, xr, y);
  double sum = 0.0;
  for (int j = -kRadius; j <= kRadius; ++j) {
    for (int i = -kRadius; i <= kRadius; ++i) sum += std::abs((left.at(x + i, y + j) - ml) - (right.at(xr + i, y + j) - mr));
  }
  return sum;
}

inline bool inside(const Gray& image, int x, int y) {
  return x >= kRadius && y >= kRadius && x < image.width() - kRadius && y < image.height() - kRadius;
}

}  // namespace patch
}  // namespace lidar_sgm
