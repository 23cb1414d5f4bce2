#include "lidar_sgm/geometry/disparity_range.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

namespace lidar_sgm {
namespace geometry {

namespace {

bool isRangeSize(int n) { return n >= 16 && n <= 512 && n % 16 == 0; }

std::string field(const char* name, double value, const char* allowed) {
  char text[160];
  std::snprintf(text, sizeof(text), "DisparityRangeRule: %s = %g, must be %s", name, value, allowed);
  return text;
}

}  // namespace

std::string validationError(const DisparityRangeRule& r) {
  if (r.ignoredPoints < 0 || r.ignoredPoints > 10000) {
    return field("ignoredPoints", r.ignoredPoints, "in [0, 10000]");
  }
  if (!(r.ignoredFraction >= 0.0 && r.ignoredFraction <= 0.5)) {
    return field("ignoredFraction", r.ignoredFraction, "in [0, 0.5]");
  }
  if (!(r.marginPx >= 0.0 && r.marginPx <= 512.0)) return field("marginPx", r.marginPx, "in [0, 512]");
  if (!(r.marginFraction >= 0.0 && r.marginFraction <= 1.0)) {
    return field("marginFraction", r.marginFraction, "in [0, 1]");
  }
  if (!isRangeSize(r.minNumDisparities)) {
    return field("minNumDisparities", r.minNumDisparities, "a multiple of 16 in [16, 512]");
  }
  if (!isRangeSize(r.maxNumDisparities) || r.maxNumDisparities < r.minNumDisparities) {
    return field("maxNumDisparities", r.maxNumDisparities,
                 "a multiple of 16 in [16, 512] and at least minNumDisparities");
  }
  return {};
}

std::string DisparityRange::describe() const {
  char text[160];
  const int top = minDisparity + numDisparities;
  if (fromLidar) {
    std::snprintf(text, sizeof(text), "[%d, %d) px from the LiDAR (max %.1f px%s)", minDisparity, top, lidarMax,
                  capped ? ", capped" : "");
  } else {
    std::snprintf(text, sizeof(text), "[%d, %d) px (fixed)", minDisparity, top);
  }
  return text;
}

int disparityGranularity(const Parameters& params) { return params.scale == 0.5f ? 32 : 16; }

DisparityRange disparityRangeFromLidar(const std::vector<LidarSample>& samples, const Parameters& fixed,
                                       const DisparityRangeRule& rule) {
  const std::string error = validationError(rule);
  if (!error.empty()) throw std::invalid_argument(error);
  DisparityRange range;
  range.minDisparity = fixed.minDisparity;
  range.numDisparities = fixed.numDisparities;
  if (samples.empty()) return range;

  // dMax: the (k+1)-th largest disparity, k = the strays set aside (nth_element: O(n)).
  std::vector<int> d16(samples.size());
  std::transform(samples.begin(), samples.end(), d16.begin(), [](const LidarSample& s) { return s.disparity16; });
  const auto byFraction = static_cast<std::size_t>(rule.ignoredFraction * static_cast<double>(d16.size()));
  const std::size_t k = std::min(static_cast<std::size_t>(rule.ignoredPoints), byFraction);
  std::nth_element(d16.begin(), d16.begin() + static_cast<std::ptrdiff_t>(k), d16.end(), std::greater<int>());
  const double dMax = std::max(0, d16[k]) / static_cast<double>(kDisparityScale);

  const int granularity = disparityGranularity(fixed);
  const double top = dMax + std::max(rule.marginPx, rule.marginFraction * dMax);
  const int cap = granularity * (rule.maxNumDisparities / granularity);
  const int floor = granularity * ((rule.minNumDisparities + granularity - 1) / granularity);
  const int wanted = granularity * static_cast<int>(std::ceil(top / granularity));
  range.minDisparity = 0;
  range.numDisparities = std::min(std::max(wanted, floor), std::max(cap, granularity));
  range.fromLidar = true;
  range.capped = wanted > cap;
  range.lidarMax = dMax;
  range.points = samples.size();
  return range;
}

}  // namespace geometry
}  // namespace lidar_sgm
