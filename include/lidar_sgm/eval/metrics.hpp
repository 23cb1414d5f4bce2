#pragma once
/// @file metrics.hpp  The paper's and KITTI's disparity metrics (docs/EVALUATION.md).

#include <cstdint>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace eval {

/// Scores over the ground-truth pixels that were not given as input.
struct DisparityMetrics {
  long gtPixels = 0;        ///< GT pixels scored
  long estimatedPixels = 0; ///< of those, pixels with an estimate
  double correct = 0;       ///< share with error < 3 px or < 5 % of GT (missing = not correct)
  double rmse = 0;          ///< RMS error over the correct pixels [px]
  double d1 = 0;            ///< share with error > 3 px and > 5 % (missing = error)
  double d1Est = 0;         ///< D1 over the pixels that have an estimate
  double density = 0;       ///< share of GT pixels with an estimate
};

/// `estimate`: x16 disparities (kInvalidDisparity = none). `groundTruth`: disparity [px],
/// <= 0 or NaN = no GT. `exclude` (optional, same size): non-zero pixels are not scored
/// (e.g. the pixels whose LiDAR value was given as input).
DisparityMetrics evaluateDisparity(ImageView<const std::int16_t> estimate,
                                   ImageView<const float> groundTruth,
                                   ImageView<const std::uint8_t> exclude = {});

/// The paper's Table II on KITTI 2015's object split: the share of wrong pixels (error > 3 px and
/// > 5 % of the GT, KITTI's D1) among the pixels that have an estimate, on the background
/// (objectMap 0), the foreground (objectMap > 0) and all GT pixels, and the density (share of GT
/// pixels with an estimate). Every GT pixel is scored (the paper excludes none). The counts behind
/// the shares are kept, for a summary over frames that sums them as KITTI's devkit does.
struct ObjectSplitMetrics {
  double background = 0;
  double foreground = 0;
  double total = 0;
  double density = 0;
  long foregroundPixels = 0;  ///< GT pixels on objects
  long gtPixels = 0;
  long estimatedBackground = 0;  ///< GT pixels with an estimate, off objects
  long estimatedForeground = 0;  ///< ... on objects
  long wrongBackground = 0;      ///< of those, wrong (> 3 px and > 5 %)
  long wrongForeground = 0;
};

/// `objectMap` has the estimate's size; std::invalid_argument otherwise. Pixels where `exclude` (if
/// not empty, the same size) is non-zero are not scored.
ObjectSplitMetrics evaluateObjectSplit(ImageView<const std::int16_t> estimate, ImageView<const float> groundTruth,
                                       ImageView<const std::uint8_t> objectMap,
                                       ImageView<const std::uint8_t> exclude = {});

/// `counts` with its shares (background, foreground, total, density) computed from its counts
/// (0 where a count they divide by is 0).
ObjectSplitMetrics withShares(ObjectSplitMetrics counts);

}  // namespace eval
}  // namespace lidar_sgm
