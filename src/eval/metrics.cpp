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

}  // namespace eval
}  // namespace lidar_sgm
