#include "lidar_sgm/eval/cloud_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lidar_sgm {
namespace eval {
namespace {

void checkInputs(const char* function, ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                 ImageView<const std::uint8_t> exclude, double focalBaseline) {
  if (estimate.width != groundTruth.width || estimate.height != groundTruth.height ||
      (!exclude.empty() && (exclude.width != estimate.width || exclude.height != estimate.height))) {
    throw std::invalid_argument(std::string(function) + ": estimate, ground truth and exclude mask differ in size");
  }
  if (!(focalBaseline > 0.0)) throw std::invalid_argument(std::string(function) + ": f*b must be > 0");
}

/// Depth of the estimate [m], or 0 where there is no point of the cloud: no disparity, a
/// disparity <= 0 (infinitely far), or farther than maxDepth (the tools drop it).
double estimatedDepth(std::int16_t disparity16, double focalBaseline, double maxDepth) {
  if (disparity16 == kInvalidDisparity || disparity16 <= 0) return 0.0;
  const double z = focalBaseline * kDisparityScale / static_cast<double>(disparity16);
  return z <= maxDepth ? z : 0.0;
}

/// GT depth [m], or 0 where the GT has no value (0, negative or NaN disparity).
double groundTruthDepth(float disparity, double focalBaseline) {
  return disparity > 0.0f ? focalBaseline / static_cast<double>(disparity) : 0.0;
}

bool isCorrect(double z, double zGt, double tau, double minTolerance) {
  return std::abs(z - zGt) <= std::max(minTolerance, tau * zGt);
}

double ratio(long numerator, long denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / static_cast<double>(denominator) : 0.0;
}

CloudScore score(long correctPoints, long points, long coveredGt, long gtPixels) {
  CloudScore s;
  s.precision = ratio(correctPoints, points);
  s.completeness = ratio(coveredGt, gtPixels);
  const double sum = s.precision + s.completeness;
  s.fScore = sum > 0.0 ? 2.0 * s.precision * s.completeness / sum : 0.0;
  return s;
}

}  // namespace

CloudMetrics evaluateCloud(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                           ImageView<const std::uint8_t> exclude, double focalBaseline, const CloudScoring& scoring) {
  checkInputs("evaluateCloud", estimate, groundTruth, exclude, focalBaseline);
  constexpr double kTau3 = 0.03;
  constexpr double kTau5 = 0.05;
  CloudMetrics m;
  long correct3 = 0, correct5 = 0;  // points within tolerance
  long covered3 = 0, covered5 = 0;  // GT pixels (z_gt <= maxDepth) with a correct point
  for (int y = 0; y < groundTruth.height; ++y) {
    for (int x = 0; x < groundTruth.width; ++x) {
      if (!exclude.empty() && exclude(x, y) != 0) continue;
      const double z = estimatedDepth(estimate(x, y), focalBaseline, scoring.maxDepth);
      const double zGt = groundTruthDepth(groundTruth(x, y), focalBaseline);
      const bool gtAsked = zGt > 0.0 && zGt <= scoring.maxDepth;
      if (gtAsked) ++m.gtPixels;
      if (z <= 0.0) continue;  // no point here
      if (zGt <= 0.0) {
        // A point where dense GT says "no surface" is wrong; where sparse GT did not measure, unknown.
        if (scoring.denseGroundTruth) ++m.points;
        continue;
      }
      ++m.points;
      const bool ok3 = isCorrect(z, zGt, kTau3, scoring.minTolerance);
      const bool ok5 = isCorrect(z, zGt, kTau5, scoring.minTolerance);
      correct3 += ok3;
      correct5 += ok5;
      if (gtAsked) {
        covered3 += ok3;
        covered5 += ok5;
      }
    }
  }
  m.tau3 = score(correct3, m.points, covered3, m.gtPixels);
  m.tau5 = score(correct5, m.points, covered5, m.gtPixels);
  return m;
}

DepthMetrics evaluateDepth(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                           ImageView<const std::uint8_t> exclude, double focalBaseline, const CloudScoring& scoring) {
  checkInputs("evaluateDepth", estimate, groundTruth, exclude, focalBaseline);
  DepthMetrics m;
  double squared = 0, absolute = 0, inverseSquared = 0, inverseAbsolute = 0;
  for (int y = 0; y < groundTruth.height; ++y) {
    for (int x = 0; x < groundTruth.width; ++x) {
      if (!exclude.empty() && exclude(x, y) != 0) continue;
      const double zGt = groundTruthDepth(groundTruth(x, y), focalBaseline);
      if (zGt <= 0.0 || zGt > scoring.maxDepth) continue;
      ++m.gtPixels;
      const double z = estimatedDepth(estimate(x, y), focalBaseline, scoring.maxDepth);
      if (z <= 0.0) continue;
      ++m.estimatedPixels;
      const double errorMm = 1000.0 * (z - zGt);
      const double inverseErrorPerKm = 1000.0 / z - 1000.0 / zGt;  // 1/m -> 1/km
      squared += errorMm * errorMm;
      absolute += std::abs(errorMm);
      inverseSquared += inverseErrorPerKm * inverseErrorPerKm;
      inverseAbsolute += std::abs(inverseErrorPerKm);
    }
  }
  if (m.estimatedPixels > 0) {
    const double n = static_cast<double>(m.estimatedPixels);
    m.rmseMm = std::sqrt(squared / n);
    m.maeMm = absolute / n;
    m.irmsePerKm = std::sqrt(inverseSquared / n);
    m.imaePerKm = inverseAbsolute / n;
  }
  m.density = ratio(m.estimatedPixels, m.gtPixels);
  return m;
}

}  // namespace eval
}  // namespace lidar_sgm
