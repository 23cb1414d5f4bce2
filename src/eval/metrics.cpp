#include "lidar_sgm/eval/metrics.hpp"

#include <cmath>
#include <stdexcept>

namespace lidar_sgm {
namespace eval {

DisparityMetrics evaluateDisparity(ImageView<const std::int16_t> estimate,
                                   ImageView<const float> groundTruth,
                                   ImageView<const std::uint8_t> exclude) {
  if (estimate.width != groundTruth.width || estimate.height != groundTruth.height ||
      (!exclude.empty() && (exclude.width != estimate.width || exclude.height != estimate.height))) {
    throw std::invalid_argument("evaluateDisparity: estimate, ground truth and exclude mask differ in size");
  }
  DisparityMetrics m;
  long correct = 0;
  long bad = 0;
  long badEstimated = 0;
  double squaredErrorSum = 0;
  for (int y = 0; y < groundTruth.height; ++y) {
    for (int x = 0; x < groundTruth.width; ++x) {
      const float gt = groundTruth(x, y);
      if (!(gt > 0.0f) || (!exclude.empty() && exclude(x, y) != 0)) continue;
      ++m.gtPixels;
      const std::int16_t e = estimate(x, y);
      if (e == kInvalidDisparity) {
        ++bad;  // a missing estimate is an error, never correct
        continue;
      }
      ++m.estimatedPixels;
      const double error = std::abs(static_cast<double>(e) / kDisparityScale - gt);
      if (error < 3.0 || error < 0.05 * gt) {
        ++correct;
        squaredErrorSum += error * error;
      }
      if (error > 3.0 && error > 0.05 * gt) {
        ++bad;
        ++badEstimated;
      }
    }
  }
  if (m.gtPixels > 0) {
    m.correct = static_cast<double>(correct) / static_cast<double>(m.gtPixels);
    m.d1 = static_cast<double>(bad) / static_cast<double>(m.gtPixels);
    m.density = static_cast<double>(m.estimatedPixels) / static_cast<double>(m.gtPixels);
  }
  if (correct > 0) m.rmse = std::sqrt(squaredErrorSum / static_cast<double>(correct));
  if (m.estimatedPixels > 0) m.d1Est = static_cast<double>(badEstimated) / static_cast<double>(m.estimatedPixels);
  return m;
}

ObjectSplitMetrics evaluateObjectSplit(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                                       ImageView<const std::uint8_t> objectMap,
                                       ImageView<const std::uint8_t> exclude) {
  if (estimate.width != groundTruth.width || estimate.height != groundTruth.height ||
      objectMap.width != estimate.width || objectMap.height != estimate.height ||
      (!exclude.empty() && (exclude.width != estimate.width || exclude.height != estimate.height))) {
    throw std::invalid_argument("evaluateObjectSplit: estimate, ground truth, object map and exclusion differ in size");
  }
  long estimated[2] = {0, 0};  // [background, foreground]
  long wrong[2] = {0, 0};
  ObjectSplitMetrics m;
  for (int y = 0; y < groundTruth.height; ++y) {
    for (int x = 0; x < groundTruth.width; ++x) {
      const float gt = groundTruth(x, y);
      if (!(gt > 0.0f) || (!exclude.empty() && exclude(x, y) != 0)) continue;
      const int object = objectMap(x, y) > 0 ? 1 : 0;
      ++m.gtPixels;
      m.foregroundPixels += object;
      const std::int16_t e = estimate(x, y);
      if (e == kInvalidDisparity) continue;
      ++estimated[object];
      const double error = std::abs(static_cast<double>(e) / kDisparityScale - gt);
      if (error > 3.0 && error > 0.05 * gt) ++wrong[object];
    }
  }
  m.estimatedBackground = estimated[0];
  m.estimatedForeground = estimated[1];
  m.wrongBackground = wrong[0];
  m.wrongForeground = wrong[1];
  return withShares(m);
}

ObjectSplitMetrics withShares(ObjectSplitMetrics m) {
  const auto share = [](long part, long whole) { return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0; };
  const long estimated = m.estimatedBackground + m.estimatedForeground;
  m.background = share(m.wrongBackground, m.estimatedBackground);
  m.foreground = share(m.wrongForeground, m.estimatedForeground);
  m.total = share(m.wrongBackground + m.wrongForeground, estimated);
  m.density = share(estimated, m.gtPixels);
  return m;
}

}  // namespace eval
}  // namespace lidar_sgm
