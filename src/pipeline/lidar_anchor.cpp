#include "lidar_sgm/pipeline/lidar_anchor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace {

int x16(double px) { return static_cast<int>(std::lround(px * 16.0)); }

bool isValid(int d) { return d != kInvalidDisparity && d > 0; }

/// Division rounded to the nearest integer, halves away from zero (the sign of `num`).
int roundedQuotient(std::int64_t num, std::int64_t den) {
  const std::int64_t q = (std::llabs(num) * 2 + den) / (den * 2);
  return static_cast<int>(num < 0 ? -q : q);
}

}  // namespace

void validate(const LidarAnchorOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("LidarAnchorOptions: " + what); };
  if (!(o.maxDisparity >= 0.0 && o.maxDisparity <= 1024.0)) fail("maxDisparity must be in [0, 1024] px");
  if (o.halfWidth < 0 || o.halfWidth > 16) fail("halfWidth must be in [0, 16] px");
  if (o.halfHeight < 0 || o.halfHeight > 16) fail("halfHeight must be in [0, 16] px");
  if (!(o.sigma >= 0.5 && o.sigma <= 16.0)) fail("sigma must be in [0.5, 16] px");
  if (!(o.agreement >= 1.0 / 16.0 && o.agreement <= 8.0)) fail("agreement must be in [1/16, 8] px");
  if (!(o.surfaceGap >= 0.0 && o.surfaceGap <= 8.0)) fail("surfaceGap must be in [0, 8] px");
}

std::size_t anchorToLidar(ImageView<std::int16_t> disparity, const std::vector<LidarSample>& samples,
                          const LidarAnchorOptions& o, LidarAnchorBuffers& buffers) {
  validate(o);
  if (!o.enabled || samples.empty() || disparity.empty() || o.maxDisparity <= 0.0) return 0;
  const int w = disparity.width;
  const int h = disparity.height;
  const int maxD = x16(o.maxDisparity);
  const int agreement = x16(o.agreement);
  const int gap = x16(o.surfaceGap);
  const int kw = 2 * o.halfWidth + 1;
  // Weights in 1/1024, 64-bit sums: any number of points may share a window.
  std::vector<int> weights(static_cast<std::size_t>(kw) * (2 * o.halfHeight + 1));
  for (int dy = -o.halfHeight; dy <= o.halfHeight; ++dy) {
    for (int dx = -o.halfWidth; dx <= o.halfWidth; ++dx) {
      weights[static_cast<std::size_t>(dy + o.halfHeight) * kw + dx + o.halfWidth] =
          static_cast<int>(std::lround(1024.0 * std::exp(-(dx * dx + dy * dy) / (2.0 * o.sigma * o.sigma))));
    }
  }
  // Only the rows within reach of a point that can anchor anything are cleared and read.
  const auto anchors = [&](const LidarSample& s, int& residual, int& dq) {
    if (s.x < 0 || s.y < 0 || s.x >= w || s.y >= h) return false;
    dq = disparity(s.x, s.y);
    // A point on a near surface reaches no far pixel of its own surface (|d(q) - d(p)| <= gap).
    if (!isValid(dq) || dq > maxD + gap) return false;
    residual = s.disparity16 - dq;
    return std::abs(residual) <= agreement;
  };
  int firstRow = h;
  int lastRow = -1;
  for (const LidarSample& s : samples) {
    int residual = 0;
    int dq = 0;
    if (!anchors(s, residual, dq)) continue;
    firstRow = std::min(firstRow, std::max(0, s.y - o.halfHeight));
    lastRow = std::max(lastRow, std::min(h - 1, s.y + o.halfHeight));
  }
  if (lastRow < firstRow) return 0;
  // The sums cover rows firstRow .. lastRow only.
  const std::size_t pixels = static_cast<std::size_t>(lastRow - firstRow + 1) * w;
  buffers.weightedResidual.assign(pixels, 0);
  buffers.weight.assign(pixels, 0);
  for (const LidarSample& s : samples) {
    int r = 0;
    int dq = 0;
    if (!anchors(s, r, dq)) continue;
    const int x0 = std::max(0, s.x - o.halfWidth);
    const int x1 = std::min(w - 1, s.x + o.halfWidth);
    for (int y = std::max(0, s.y - o.halfHeight); y <= std::min(h - 1, s.y + o.halfHeight); ++y) {
      const int* weightRow = weights.data() + static_cast<std::size_t>(y - s.y + o.halfHeight) * kw;
      const std::int16_t* row = &disparity(0, y);
      std::int64_t* sumRow = buffers.weightedResidual.data() + static_cast<std::size_t>(y - firstRow) * w;
      std::int64_t* weightSumRow = buffers.weight.data() + static_cast<std::size_t>(y - firstRow) * w;
      for (int x = x0; x <= x1; ++x) {
        const int dp = row[x];
        if (!isValid(dp) || dp > maxD || std::abs(dp - dq) > gap) continue;
        const int weight = weightRow[x - s.x + o.halfWidth];
        sumRow[x] += weight * r;
        weightSumRow[x] += weight;
      }
    }
  }
  std::size_t moved = 0;
  for (int y = firstRow; y <= lastRow; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y - firstRow) * w + x;
      if (buffers.weight[i] == 0) continue;
      const int correction = roundedQuotient(buffers.weightedResidual[i], buffers.weight[i]);
      const int d = disparity(x, y) + correction;
      if (correction == 0 || d <= 0) continue;  // never a point at or behind infinity
      disparity(x, y) = static_cast<std::int16_t>(d);
      ++moved;
    }
  }
  return moved;
}

}  // namespace lidar_sgm
