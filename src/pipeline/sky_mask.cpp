#include "lidar_sgm/pipeline/sky_mask.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "texture_map.hpp"

namespace lidar_sgm {

namespace {

constexpr int kNoSample = std::numeric_limits<int>::max();

/// Per column, over +-radius columns: the highest (smallest) sample row and the smallest sample
/// disparity; kNoSample where no sample lies within reach.
void scanExtent(const std::vector<LidarSample>& samples, int width, int height, int radius, std::vector<int>& top,
                std::vector<int>& minDisparity16) {
  std::vector<int> columnTop(static_cast<std::size_t>(width), kNoSample);
  std::vector<int> columnMin(static_cast<std::size_t>(width), kNoSample);
  for (const LidarSample& s : samples) {
    if (s.x < 0 || s.x >= width || s.y < 0 || s.y >= height) {
      throw std::invalid_argument("removeSky: a LiDAR sample lies outside the disparity image");
    }
    columnTop[s.x] = std::min(columnTop[s.x], s.y);
    columnMin[s.x] = std::min(columnMin[s.x], s.disparity16);
  }
  top.assign(static_cast<std::size_t>(width), kNoSample);
  minDisparity16.assign(static_cast<std::size_t>(width), kNoSample);
  for (int x = 0; x < width; ++x) {
    for (int xx = std::max(0, x - radius); xx <= std::min(width - 1, x + radius); ++xx) {
      top[x] = std::min(top[x], columnTop[xx]);
      minDisparity16[x] = std::min(minDisparity16[x], columnMin[xx]);
    }
  }
}

/// Whether a mask has a set pixel in a square window (integral image: exact, any order).
class MaskCounter {
 public:
  MaskCounter(const std::vector<std::uint8_t>& mask, int width, int height)
      : width_(width), height_(height), sums_((static_cast<std::size_t>(width) + 1) * (height + 1), 0) {
    const std::size_t stride = static_cast<std::size_t>(width) + 1;
    for (int y = 0; y < height; ++y) {
      long row = 0;
      for (int x = 0; x < width; ++x) {
        row += mask[static_cast<std::size_t>(y) * width + x];
        sums_[(y + 1) * stride + x + 1] = sums_[y * stride + x + 1] + row;
      }
    }
  }
  bool any(int x, int y, int radius) const {
    const std::size_t stride = static_cast<std::size_t>(width_) + 1;
    const int x0 = std::max(0, x - radius);
    const int x1 = std::min(width_ - 1, x + radius) + 1;
    const int y0 = std::max(0, y - radius);
    const int y1 = std::min(height_ - 1, y + radius) + 1;
    return sums_[y1 * stride + x1] - sums_[y0 * stride + x1] - sums_[y1 * stride + x0] + sums_[y0 * stride + x0] > 0;
  }

 private:
  int width_;
  int height_;
  std::vector<long> sums_;
};

}  // namespace

void validate(const SkyFilterOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("SkyFilterOptions: " + what); };
  if (o.marginRows < 0) fail("marginRows must be >= 0, got " + std::to_string(o.marginRows));
  if (o.columnRadius < 0 || o.columnRadius > 256) {
    fail("columnRadius must be in [0, 256], got " + std::to_string(o.columnRadius));
  }
  if (!(o.farSlack >= 0.0 && o.farSlack <= 64.0)) fail("farSlack must be in [0, 64] px, got " + std::to_string(o.farSlack));
  if (o.textureRadius < 1 || o.textureRadius > 32) {
    fail("textureRadius must be in [1, 32], got " + std::to_string(o.textureRadius));
  }
  if (!(o.textureThreshold >= 0.0 && o.textureThreshold <= 510.0)) {
    fail("textureThreshold must be in [0, 510] levels per pixel, got " + std::to_string(o.textureThreshold));
  }
  if (o.brightLevel < 0 || o.brightLevel > 256) {
    fail("brightLevel must be in [0, 256] (256 = never), got " + std::to_string(o.brightLevel));
  }
}

std::size_t removeSky(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                      const GrayImageView& left, const SkyFilterOptions& options) {
  validate(options);
  if (!options.enabled || samples.empty()) return 0;
  const int width = disparity16.width;
  const int height = disparity16.height;
  if (!left.empty() && (left.width() != width || left.height() != height)) {
    throw std::invalid_argument("removeSky: the left image and the disparity image differ in size");
  }
  std::vector<int> top;
  std::vector<int> minDisparity16;
  scanExtent(samples, width, height, options.columnRadius, top, minDisparity16);
  const TextureMap texture(left, options.textureRadius);
  const int farSlack16 = static_cast<int>(std::lround(options.farSlack * kDisparityScale));

  // Sky-like: above the scan (no return in the column above, with the margin; a column without
  // any return nearby is all candidate), and far (farther than anything the LiDAR saw nearby,
  // d < smallest LiDAR d - slack, Eq. 3) or bright and blank.
  const auto at = [width](int x, int y) { return static_cast<std::size_t>(y) * width + x; };
  std::vector<std::uint8_t> candidate(static_cast<std::size_t>(width) * height, 0);
  std::vector<std::uint8_t> skyLike(candidate.size(), 0);
  for (int x = 0; x < width; ++x) {
    const int candidateEnd = top[x] == kNoSample ? height : std::max(0, top[x] - options.marginRows);
    for (int y = 0; y < candidateEnd; ++y) {
      candidate[at(x, y)] = 1;
      const int d = disparity16(x, y);
      const bool far = options.farTest && d != kInvalidDisparity && minDisparity16[x] != kNoSample &&
                       d < minDisparity16[x] - farSlack16;
      const bool brightBlank = !texture.empty() && texture.level8(x, y) >= options.brightLevel &&
                               texture.meanGradientBelow(x, y, options.textureThreshold);
      skyLike[at(x, y)] = far || brightBlank ? 1 : 0;
    }
  }
  // The sky reaches the top of the image: the sky-like pixels 4-connected to the top row (a
  // connected component, whatever the visiting order). A bright blank facade under a cornice, or
  // anything below structure that reaches above the top beam, is not connected and stays.
  std::vector<std::uint8_t> sky(candidate.size(), 0);
  std::vector<std::size_t> stack;
  for (int x = 0; x < width; ++x) {
    if (skyLike[at(x, 0)] != 0) {
      sky[at(x, 0)] = 1;
      stack.push_back(at(x, 0));
    }
  }
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    const int x = static_cast<int>(i % static_cast<std::size_t>(width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(width));
    const int nx[4] = {x - 1, x + 1, x, x};
    const int ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || nx[k] >= width || ny[k] < 0 || ny[k] >= height) continue;
      const std::size_t j = at(nx[k], ny[k]);
      if (skyLike[j] != 0 && sky[j] == 0) {
        sky[j] = 1;
        stack.push_back(j);
      }
    }
  }
  // The rim: a bright candidate pixel within textureRadius of the sky is sky too (its texture
  // window straddles the edge of what stands in front, so it is not blank itself).
  std::vector<std::uint8_t> rim(candidate.size(), 0);
  if (!texture.empty()) {
    const MaskCounter near(sky, width, height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = at(x, y);
        rim[i] = candidate[i] != 0 && sky[i] == 0 && texture.level8(x, y) >= options.brightLevel &&
                         near.any(x, y, options.textureRadius)
                     ? 1
                     : 0;
      }
    }
  }
  std::size_t removed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::int16_t& d = disparity16(x, y);
      if ((sky[at(x, y)] != 0 || rim[at(x, y)] != 0) && d != kInvalidDisparity) {
        d = kInvalidDisparity;
        ++removed;
      }
    }
  }
  return removed;
}

}  // namespace lidar_sgm
