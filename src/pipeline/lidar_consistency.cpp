#include "lidar_sgm/pipeline/lidar_consistency.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "patch_match.hpp"

namespace lidar_sgm {
namespace {

using patch::Gray;
using patch::kArea;
using patch::kRadius;

/// The right image's 7x7 patch means, once per frame: a candidate then costs one patch
/// difference, not two.
std::vector<float> patchMeans(const Gray& image) {
  const int w = image.width();
  const int h = image.height();
  std::vector<float> means(static_cast<std::size_t>(w) * h, 0.0f);
  std::vector<long> columns(static_cast<std::size_t>(w));
  for (int y = kRadius; y < h - kRadius; ++y) {
    for (int x = 0; x < w; ++x) {
      long sum = 0;
      for (int j = -kRadius; j <= kRadius; ++j) sum += image.at(x, y + j);
      columns[static_cast<std::size_t>(x)] = sum;
    }
    for (int x = kRadius; x < w - kRadius; ++x) {
      long sum = 0;
      for (int i = -kRadius; i <= kRadius; ++i) sum += columns[static_cast<std::size_t>(x + i)];
      means[static_cast<std::size_t>(y) * w + x] = static_cast<float>(sum) / kArea;
    }
  }
  return means;
}

}  // namespace

void validate(const LidarConsistencyOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("LidarConsistencyOptions: " + what); };
  if (!(o.costRatio >= 1.0 && o.costRatio <= 100.0)) fail("costRatio must be in [1, 100]");
  if (!(o.marginPerPixel >= 0.0 && o.marginPerPixel <= 255.0)) fail("marginPerPixel must be in [0, 255]");
  if (o.searchRadius < 4 || o.searchRadius > 256) fail("searchRadius must be in [4, 256]");
  if (!(o.minDisagreement >= 1.0 && o.minDisagreement <= 64.0)) fail("minDisagreement must be in [1, 64]");
}

std::size_t dropInconsistentLidar(const GrayImageView& leftView, const GrayImageView& rightView,
                                  std::vector<LidarSample>& samples, const LidarConsistencyOptions& o) {
  validate(o);
  if (!o.enabled || samples.empty() || leftView.empty() || rightView.empty()) return 0;
  const Gray left(leftView);
  const Gray right(rightView);
  const int w = left.width();
  const std::vector<float> rightMeans = patchMeans(right);
  const double margin = o.marginPerPixel * kArea * (left.g8.empty() ? 257.0 : 1.0);
  std::array<float, kArea> patch{};
  const auto keep = [&](const LidarSample& s) {
    const int d = (s.disparity16 + 8) / 16;
    if (d < 1 || !patch::inside(left, s.x, s.y) || s.x - d - 1 < kRadius) return true;
    const double mean = patch::patchMean(left, s.x, s.y);
    if (patch::patchTexture(left, s.x, s.y, mean) < left.flatness()) return true;
    int k = 0;
    for (int j = -kRadius; j <= kRadius; ++j) {
      for (int i = -kRadius; i <= kRadius; ++i) patch[k++] = static_cast<float>(left.at(s.x + i, s.y + j) - mean);
    }
    const auto cost = [&](int disparity) {  // zero-mean SAD against the right patch at x - disparity
      const int xr = s.x - disparity;
      const float mr = rightMeans[static_cast<std::size_t>(s.y) * w + xr];
      float sad = 0.0f;
      int n = 0;
      for (int j = -kRadius; j <= kRadius; ++j) {
        for (int i = -kRadius; i <= kRadius; ++i) sad += std::abs(patch[n++] - (static_cast<float>(right.at(xr + i, s.y + j)) - mr));
      }
      return static_cast<double>(sad);
    };
    const double atPoint = std::min({cost(d - 1), cost(d), d + 1 <= s.x - kRadius ? cost(d + 1) : cost(d)});
    double best = std::numeric_limits<double>::infinity();
    int bestDisparity = d;
    const int last = std::min(d + o.searchRadius, s.x - kRadius);
    for (int c = std::max(0, d - o.searchRadius); c <= last; ++c) {
      const double sad = cost(c);
      if (sad < best) {
        best = sad;
        bestDisparity = c;
      }
    }
    const bool contradicted = atPoint > o.costRatio * best + margin &&
                              std::abs(bestDisparity - static_cast<double>(s.disparity16) / 16.0) > o.minDisagreement;
    return !contradicted;
  };
  const std::size_t before = samples.size();
  samples.erase(std::remove_if(samples.begin(), samples.end(), [&](const LidarSample& s) { return !keep(s); }),
                samples.end());
  return before - samples.size();
}

}  // namespace lidar_sgm
