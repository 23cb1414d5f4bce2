#pragma once
/// @file confidence_curves.hpp  How good a per-pixel confidence (core/confidence.hpp) is, from a
/// method's disparity and confidence alone (the matcher is not run again):
///  - the precision/completeness curve: the cloud metrics (cloud_metrics.hpp) after dropping the
///    pixels below each minimum confidence, as Densifier::setMinConfidence drops them;
///  - the sparsification curve: the share of wrong pixels among those kept after removing the
///    least confident fraction f, beside the oracle that removes the wrong pixels first, and the
///    area under each (the standard measure of a confidence map, e.g. Hu and Mordohai 2012).

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/eval/cloud_metrics.hpp"

namespace lidar_sgm {
namespace eval {

/// The minimum confidences of the curve: 0, 0.1, ..., 0.9, 0.95.
const std::vector<double>& confidenceThresholds();

/// The removed fractions of the sparsification curve: 0, 0.05, ..., 0.95.
const std::vector<double>& sparsificationFractions();

/// `estimate` with every pixel whose confidence is below `minConfidence` in [0, 1] made
/// kInvalidDisparity: confidence / 255 < minConfidence, i.e. confidence < ceil(255 * minConfidence),
/// the rule of Densifier::setMinConfidence. Throws std::invalid_argument when the sizes differ or
/// minConfidence is outside [0, 1].
Image<std::int16_t> dropBelowConfidence(ImageView<const std::int16_t> estimate,
                                        ImageView<const std::uint8_t> confidence, double minConfidence);

/// A sparsification curve of one frame.
struct Sparsification {
  std::vector<double> fractions;  ///< removed fraction f of each point
  std::vector<double> error;      ///< share of wrong pixels among the kept, sorted by confidence
  std::vector<double> oracle;     ///< the same, sorted by the true error (the best any confidence can do)
  double auc = 0;        ///< mean of `error` over the fractions
  double oracleAuc = 0;  ///< mean of `oracle`
  double aucGap = 0;     ///< auc - oracleAuc (0: the confidence ranks as well as the truth)
  long pixels = 0;       ///< the pixels ranked: a disparity and GT, not excluded
};

/// The sparsification curve at `fractions` (each in [0, 1)). The pixels ranked have an estimate
/// (not kInvalidDisparity), GT > 0 and are not excluded; one is wrong by KITTI's criterion, error
/// > 3 px and > 5 % of the GT (so at f = 0 the error is DisparityMetrics::d1Est). Removing f of n
/// pixels keeps n - floor(f * n). Pixels of equal confidence are ranked as if in random order: the
/// kept pixels of the confidence at the cut count with that level's share of wrong pixels, so a
/// constant confidence gives a flat curve whatever the pixel order. All zero when no pixel is
/// ranked. Throws std::invalid_argument on differing sizes or a fraction outside [0, 1).
Sparsification sparsify(ImageView<const std::int16_t> estimate, ImageView<const std::uint8_t> confidence,
                        ImageView<const float> groundTruth, ImageView<const std::uint8_t> exclude,
                        const std::vector<double>& fractions = sparsificationFractions());

/// Both curves of one method on one frame; empty when the method has no confidence.
struct ConfidenceCurves {
  std::vector<double> thresholds;  ///< minimum confidences, in [0, 1]
  std::vector<CloudMetrics> cloud;  ///< the cloud metrics at each threshold
  Sparsification sparsification;
  bool empty() const { return thresholds.empty(); }
};

/// The cloud metrics (evaluateCloud with `scoring`) after dropBelowConfidence at each threshold,
/// and sparsify at `fractions`. Throws as those do.
ConfidenceCurves confidenceCurves(ImageView<const std::int16_t> estimate, ImageView<const std::uint8_t> confidence,
                                  ImageView<const float> groundTruth, ImageView<const std::uint8_t> exclude,
                                  double focalBaseline, const CloudScoring& scoring = {},
                                  const std::vector<double>& thresholds = confidenceThresholds(),
                                  const std::vector<double>& fractions = sparsificationFractions());

/// Medians over frames, as the other tables: per threshold medianCloud; per fraction the median
/// error and oracle error, and per-field medians of auc, oracleAuc and aucGap (so the median gap
/// is not the gap of the medians), over the frames that ranked pixels (pixels summed). Empty
/// curves are skipped; all must share thresholds and fractions (std::invalid_argument otherwise).
ConfidenceCurves medianCurves(const std::vector<ConfidenceCurves>& curves);

}  // namespace eval
}  // namespace lidar_sgm
