#include "lidar_sgm/pipeline/lidar_anchor.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "pipeline/lidar_anchor_rows.hpp"

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

bool AnchorPlan::anchors(ImageView<const std::int16_t> disparity, const LidarSample& s, int& residual, int& dq) const {
  if (s.x < 0 || s.y < 0 || s.x >= disparity.width || s.y >= disparity.height) return false;
  dq = disparity(s.x, s.y);
  // A point on a near surface reaches no far pixel of its own surface (|d(q) - d(p)| <= gap).
  if (!isValid(dq) || dq > maxD + gap) return false;
  residual = s.disparity16 - dq;
  return std::abs(residual) <= agreement;
}

bool planAnchoring(ImageView<const std::int16_t> disparity, const std::vector<LidarSample>& samples,
                   const LidarAnchorOptions& o, AnchorPlan& plan, LidarAnchorBuffers& buffers) {
  validate(o);
  if (!o.enabled || samples.empty() || disparity.empty() || o.maxDisparity <= 0.0) return false;
  plan.options = o;
  plan.maxD = x16(o.maxDisparity);
  plan.agreement = x16(o.agreement);
  plan.gap = x16(o.surfaceGap);
  const int kw = 2 * o.halfWidth + 1;
  // Weights in 1/1024, 64-bit sums: any number of points may share a window.
  plan.weights.resize(static_cast<std::size_t>(kw) * (2 * o.halfHeight + 1));
  for (int dy = -o.halfHeight; dy <= o.halfHeight; ++dy) {
    for (int dx = -o.halfWidth; dx <= o.halfWidth; ++dx) {
      plan.weights[static_cast<std::size_t>(dy + o.halfHeight) * kw + dx + o.halfWidth] =
          static_cast<int>(std::lround(1024.0 * std::exp(-(dx * dx + dy * dy) / (2.0 * o.sigma * o.sigma))));
    }
  }
  // Only the rows within reach of a point that can anchor anything are cleared and read.
  plan.firstRow = disparity.height;
  plan.lastRow = -1;
  for (const LidarSample& s : samples) {
    int residual = 0;
    int dq = 0;
    if (!plan.anchors(disparity, s, residual, dq)) continue;
    plan.firstRow = std::min(plan.firstRow, std::max(0, s.y - o.halfHeight));
    plan.lastRow = std::max(plan.lastRow, std::min(disparity.height - 1, s.y + o.halfHeight));
  }
  if (plan.lastRow < plan.firstRow) return false;
  // The sums cover rows firstRow .. lastRow only; each caller of accumulateAnchors clears its rows.
  const std::size_t pixels = static_cast<std::size_t>(plan.lastRow - plan.firstRow + 1) * disparity.width;
  buffers.weightedResidual.resize(pixels);
  buffers.weight.resize(pixels);
  return true;
}

void accumulateAnchors(ImageView<const std::int16_t> disparity, const std::vector<LidarSample>& samples,
                       const AnchorPlan& plan, int y0, int y1, LidarAnchorBuffers& buffers) {
  const LidarAnchorOptions& o = plan.options;
  const int w = disparity.width;
  const int kw = 2 * o.halfWidth + 1;
  const std::size_t begin = static_cast<std::size_t>(y0 - plan.firstRow) * w;
  const std::size_t end = static_cast<std::size_t>(y1 - plan.firstRow) * w;
  std::fill(buffers.weightedResidual.begin() + static_cast<std::ptrdiff_t>(begin),
            buffers.weightedResidual.begin() + static_cast<std::ptrdiff_t>(end), 0);
  std::fill(buffers.weight.begin() + static_cast<std::ptrdiff_t>(begin),
            buffers.weight.begin() + static_cast<std::ptrdiff_t>(end), 0);
  for (const LidarSample& s : samples) {
    if (s.y + o.halfHeight < y0 || s.y - o.halfHeight >= y1) continue;  // its window misses the rows
    int r = 0;
    int dq = 0;
    if (!plan.anchors(disparity, s, r, dq)) continue;
    const int x0 = std::max(0, s.x - o.halfWidth);
    const int x1 = std::min(w - 1, s.x + o.halfWidth);
    for (int y = std::max(y0, s.y - o.halfHeight); y <= std::min(y1 - 1, s.y + o.halfHeight); ++y) {
      const int* weightRow = plan.weights.data() + static_cast<std::size_t>(y - s.y + o.halfHeight) * kw;
      const std::int16_t* row = &disparity(0, y);
      std::int64_t* sumRow = buffers.weightedResidual.data() + static_cast<std::size_t>(y - plan.firstRow) * w;
      std::int64_t* weightSumRow = buffers.weight.data() + static_cast<std::size_t>(y - plan.firstRow) * w;
      for (int x = x0; x <= x1; ++x) {
        const int dp = row[x];
        if (!isValid(dp) || dp > plan.maxD || std::abs(dp - dq) > plan.gap) continue;
        const int weight = weightRow[x - s.x + o.halfWidth];
        sumRow[x] += weight * r;
        weightSumRow[x] += weight;
      }
    }
  }
}

std::size_t correctAnchored(ImageView<std::int16_t> disparity, const AnchorPlan& plan, int y0, int y1,
                            const LidarAnchorBuffers& buffers) {
  const int w = disparity.width;
  std::size_t moved = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y - plan.firstRow) * w + x;
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

std::size_t anchorToLidar(ImageView<std::int16_t> disparity, const std::vector<LidarSample>& samples,
                          const LidarAnchorOptions& o, LidarAnchorBuffers& buffers) {
  AnchorPlan plan;
  if (!planAnchoring(disparity, samples, o, plan, buffers)) return 0;
  accumulateAnchors(disparity, samples, plan, plan.firstRow, plan.lastRow + 1, buffers);
  return correctAnchored(disparity, plan, plan.firstRow, plan.lastRow + 1, buffers);
}

}  // namespace lidar_sgm
