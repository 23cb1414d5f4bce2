#include "lidar_sgm/pipeline/hidden_lidar.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
void validate(const HiddenLidarOptions& o) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("HiddenLidarOptions: " + what); };
  if (!(o.minGap >= 0.5 && o.minGap <= 64.0)) fail("minGap must be in [0.5, 64] px");
  if (!(o.relativeGap >= 0.0 && o.relativeGap <= 1.0)) fail("relativeGap must be in [0, 1]");
  if (o.halfWidth < 0 || o.halfWidth > 16) fail("halfWidth must be in [0, 16] px");
  if (o.supportHalfWidth < 0 || o.supportHalfWidth > 64) fail("supportHalfWidth must be in [0, 64] px");
  if (o.supportHalfHeight < 0 || o.supportHalfHeight > 64) fail("supportHalfHeight must be in [0, 64] px");
  if (o.witnessScale != 1.0f && o.witnessScale != 0.5f && o.witnessScale != 0.25f) {
    fail("witnessScale must be 1, 0.5 or 0.25");
  }
  if (o.witnessMarginRows < 0 || o.witnessMarginRows > 4096) fail("witnessMarginRows must be in [0, 4096] rows");
}

WitnessRows witnessRows(const std::vector<LidarSample>& samples, int height, int marginRows, int block) {
  int top = height;
  int bottom = -1;
  for (const LidarSample& s : samples) {
    if (s.y < 0 || s.y >= height) continue;  // outside the image: never read
    top = std::min(top, s.y);
    bottom = std::max(bottom, s.y);
  }
  WitnessRows rows;
  if (bottom < top) return rows;
  rows.begin = std::max(0, top - marginRows) / block * block;
  rows.end = std::min(height, (std::min(height, bottom + 1 + marginRows) + block - 1) / block * block);
  return rows;
}

std::size_t dropHiddenLidar(ImageView<const std::int16_t> stereo, const LidarPoints& scan,
                            std::vector<LidarSample>& samples, const HiddenLidarOptions& o) {
  validate(o);
  if (!o.enabled || samples.empty() || stereo.empty()) return 0;
  if (scan.width() != stereo.width || scan.height() != stereo.height) {
    throw std::invalid_argument("dropHiddenLidar: the scan is " + std::to_string(scan.width()) + "x" +
                                std::to_string(scan.height()) + " but the stereo disparity " +
                                std::to_string(stereo.width) + "x" + std::to_string(stereo.height));
  }
  const int w = stereo.width;
  const int h = stereo.height;
  // Compared in x16 fixed point, as both disparities are stored.
  const double minGap16 = 16.0 * o.minGap;
  const auto hidden = [&](const LidarSample& s) {
    if (s.x < 0 || s.y < 0 || s.x >= w || s.y >= h) return false;
    // No vote where the left-right check found the pixel occluded: that is where a right
    // background point beside a nearer object lies.
    if (stereo(s.x, s.y) == kInvalidDisparity) return false;
    // The farthest stereo surface within +-halfWidth columns: stereo fattens a near object's edge
    // over the background by a few pixels (the census window), and a right background point
    // beside that edge must not be judged by the fattened disparity.
    int seen = std::numeric_limits<int>::max();
    for (int x = std::max(0, s.x - o.halfWidth); x <= std::min(w - 1, s.x + o.halfWidth); ++x) {
      const std::int16_t d = stereo(x, s.y);
      if (d != kInvalidDisparity) seen = std::min(seen, static_cast<int>(d));
    }
    const double gap16 = static_cast<double>(seen) - s.disparity16;
    if (!(gap16 > minGap16 && gap16 > o.relativeGap * s.disparity16)) return false;
    // The LiDAR itself must vouch for the nearer surface: another point nearby at the stereo
    // disparity (the object the point was seen past, the car body around a window). A nearer
    // stereo disparity no point confirms is more often stereo's own mistake.
    for (int y = std::max(0, s.y - o.supportHalfHeight); y <= std::min(h - 1, s.y + o.supportHalfHeight); ++y) {
      for (int x = std::max(0, s.x - o.supportHalfWidth); x <= std::min(w - 1, s.x + o.supportHalfWidth); ++x) {
        if (scan.count(x, y) == 0) continue;
        const int nearest = *std::max_element(scan.begin(x, y), scan.end(x, y));  // the pixel's nearest point
        if (std::abs(nearest - seen) <= minGap16) return true;
      }
    }
    return false;
  };
  const std::size_t before = samples.size();
  samples.erase(std::remove_if(samples.begin(), samples.end(), hidden), samples.end());
  return before - samples.size();
}

}  // namespace lidar_sgm
