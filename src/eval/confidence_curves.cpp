#include "lidar_sgm/eval/confidence_curves.hpp"

#include "lidar_sgm/pipeline/min_confidence.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

void checkSize(const char* function, ImageView<const std::int16_t> estimate, int width, int height, const char* what) {
  if (estimate.width != width || estimate.height != height) {
    throw std::invalid_argument(std::string(function) + ": " + what + " is " + std::to_string(width) + "x" +
                                std::to_string(height) + ", the estimate " + std::to_string(estimate.width) + "x" +
                                std::to_string(estimate.height));
  }
}

/// KITTI's criterion (metrics.cpp): wrong when the error is > 3 px and > 5 % of the GT.
bool isWrong(std::int16_t estimate16, float groundTruth) {
  const double error = std::abs(static_cast<double>(estimate16) / kDisparityScale - groundTruth);
  return error > 3.0 && error > 0.05 * groundTruth;
}

double mean(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

}  // namespace

const std::vector<double>& confidenceThresholds() {
  static const std::vector<double> thresholds{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
  return thresholds;
}

const std::vector<double>& sparsificationFractions() {
  static const std::vector<double> fractions = [] {
    std::vector<double> f;
    for (int i = 0; i < 20; ++i) f.push_back(0.05 * i);
    return f;
  }();
  return fractions;
}

Image<std::int16_t> dropBelowConfidence(ImageView<const std::int16_t> estimate,
                                        ImageView<const std::uint8_t> confidence, double minConfidence) {
  checkSize("dropBelowConfidence", estimate, confidence.width, confidence.height, "the confidence");
  if (!(minConfidence >= 0.0 && minConfidence <= 1.0)) {
    throw std::invalid_argument("dropBelowConfidence: minConfidence = " + std::to_string(minConfidence) +
                                ", must be in [0, 1]");
  }
  // The Densifier's own threshold, so the curve is what the tools ship.
  const int threshold = confidenceThreshold(minConfidence);
  Image<std::int16_t> kept(estimate.width, estimate.height);
  for (int y = 0; y < estimate.height; ++y) {
    for (int x = 0; x < estimate.width; ++x) {
      kept(x, y) = confidence(x, y) >= threshold ? estimate(x, y) : kInvalidDisparity;
    }
  }
  return kept;
}

Sparsification sparsify(ImageView<const std::int16_t> estimate, ImageView<const std::uint8_t> confidence,
                        ImageView<const float> groundTruth, ImageView<const std::uint8_t> exclude,
                        const std::vector<double>& fractions) {
  checkSize("sparsify", estimate, confidence.width, confidence.height, "the confidence");
  checkSize("sparsify", estimate, groundTruth.width, groundTruth.height, "the ground truth");
  if (!exclude.empty()) checkSize("sparsify", estimate, exclude.width, exclude.height, "the exclude mask");
  for (double f : fractions) {
    if (!(f >= 0.0 && f < 1.0)) {
      throw std::invalid_argument("sparsify: fraction " + std::to_string(f) + " is outside [0, 1)");
    }
  }
  // Per confidence level: ranked pixels and wrong ones. The confidence is 8-bit, so counting by
  // level is the sort, and ties are whole levels.
  std::array<long, 256> pixels{}, wrong{};
  Sparsification s;
  long totalWrong = 0;
  for (int y = 0; y < estimate.height; ++y) {
    for (int x = 0; x < estimate.width; ++x) {
      const std::int16_t e = estimate(x, y);
      const float gt = groundTruth(x, y);
      if (e == kInvalidDisparity || !(gt > 0.0f) || (!exclude.empty() && exclude(x, y) != 0)) continue;
      const bool bad = isWrong(e, gt);
      ++pixels[confidence(x, y)];
      wrong[confidence(x, y)] += bad;
      ++s.pixels;
      totalWrong += bad;
    }
  }
  s.fractions = fractions;
  for (double f : fractions) {
    if (s.pixels == 0) {
      s.error.push_back(0.0);
      s.oracle.push_back(0.0);
      continue;
    }
    const long keep = s.pixels - static_cast<long>(std::floor(f * static_cast<double>(s.pixels) + 1e-9));
    // Most confident first; the level at the cut contributes its share of wrong pixels.
    double keptWrong = 0;
    long left = keep;
    for (int level = 255; level >= 0 && left > 0; --level) {
      const long take = std::min(left, pixels[level]);
      if (take == 0) continue;
      keptWrong += take == pixels[level] ? static_cast<double>(wrong[level])
                                         : static_cast<double>(wrong[level]) * static_cast<double>(take) /
                                               static_cast<double>(pixels[level]);
      left -= take;
    }
    s.error.push_back(keptWrong / static_cast<double>(keep));
    // The oracle removes the wrong pixels first.
    const long removed = s.pixels - keep;
    s.oracle.push_back(static_cast<double>(std::max(0L, totalWrong - removed)) / static_cast<double>(keep));
  }
  s.auc = mean(s.error);
  s.oracleAuc = mean(s.oracle);
  s.aucGap = s.auc - s.oracleAuc;
  return s;
}

ConfidenceCurves confidenceCurves(ImageView<const std::int16_t> estimate, ImageView<const std::uint8_t> confidence,
                                  ImageView<const float> groundTruth, ImageView<const std::uint8_t> exclude,
                                  double focalBaseline, const CloudScoring& scoring,
                                  const std::vector<double>& thresholds, const std::vector<double>& fractions) {
  ConfidenceCurves curves;
  curves.thresholds = thresholds;
  for (double t : thresholds) {
    const Image<std::int16_t> kept = dropBelowConfidence(estimate, confidence, t);
    curves.cloud.push_back(evaluateCloud(kept.view(), groundTruth, exclude, focalBaseline, scoring));
  }
  curves.sparsification = sparsify(estimate, confidence, groundTruth, exclude, fractions);
  return curves;
}

ConfidenceCurves medianCurves(const std::vector<ConfidenceCurves>& curves) {
  ConfidenceCurves median;
  std::vector<const ConfidenceCurves*> used;
  for (const ConfidenceCurves& c : curves) {
    if (c.empty()) continue;
    if (!used.empty() && (c.thresholds != used.front()->thresholds ||
                          c.sparsification.fractions != used.front()->sparsification.fractions)) {
      throw std::invalid_argument("medianCurves: the frames' thresholds or fractions differ");
    }
    used.push_back(&c);
  }
  if (used.empty()) return median;
  median.thresholds = used.front()->thresholds;
  for (std::size_t t = 0; t < median.thresholds.size(); ++t) {
    std::vector<CloudMetrics> atThreshold;
    for (const ConfidenceCurves* c : used) atThreshold.push_back(c->cloud[t]);
    median.cloud.push_back(medianCloud(atThreshold));
  }
  Sparsification& s = median.sparsification;
  s.fractions = used.front()->sparsification.fractions;
  std::vector<const Sparsification*> ranked;  // frames without ranked pixels have no curve
  for (const ConfidenceCurves* c : used) {
    if (c->sparsification.pixels > 0) ranked.push_back(&c->sparsification);
  }
  const auto medianField = [&](auto field) {
    std::vector<double> values;
    for (const Sparsification* r : ranked) values.push_back(field(*r));
    return medianOf(values);
  };
  for (std::size_t i = 0; i < s.fractions.size(); ++i) {
    s.error.push_back(medianField([i](const Sparsification& r) { return r.error[i]; }));
    s.oracle.push_back(medianField([i](const Sparsification& r) { return r.oracle[i]; }));
  }
  s.auc = medianField([](const Sparsification& r) { return r.auc; });
  s.oracleAuc = medianField([](const Sparsification& r) { return r.oracleAuc; });
  s.aucGap = medianField([](const Sparsification& r) { return r.aucGap; });
  for (const Sparsification* r : ranked) s.pixels += r->pixels;
  return median;
}

}  // namespace eval
}  // namespace lidar_sgm
