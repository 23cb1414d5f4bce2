#pragma once
/// @file stages.hpp  The stages of LiDAR-SGM, one function each, named as in the paper.
///
/// The functions in namespace `cpu_ref` are the specification: naive, readable loops. Every faster
/// backend implements the same signatures in its own namespace and is tested against these
/// stage by stage, bit for bit.

#include <cmath>
#include <cstdint>

#include "backends/common/cost_volume.hpp"
#include "backends/common/host_device.hpp"
#include "core/fixed_point.hpp"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "backends/common/lidar_cost_table.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {

/// Largest census cost for either census type (9x7 census: 62 bits; the centre-symmetric
/// variant's 31 bits are counted twice so both types share one range).
constexpr int kMaxCensusCost = 62;
/// C_S where the right image has no counterpart (x - d outside it): the expected Hamming
/// distance of two unrelated census strings, i.e. "no information", favouring no disparity.
constexpr int kNoCounterpartCensusCost = kMaxCensusCost / 2;

/// a / b rounded toward minus infinity (b > 0), as C++'s / is not for a negative a.
LIDAR_SGM_HOST_DEVICE inline int floorDivide(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/// Triple-SGM: the vertical disparity [rows] of the absolute horizontal disparity `d`,
/// dv = (d * ratio16 + 32768) >> 16, i.e. d * b_up / b rounded half up (floor, also for d < 0).
LIDAR_SGM_HOST_DEVICE inline int verticalDisparity(int d, int ratio16) {
  const int scaled = d * ratio16 + 32768;  // |d| <= 1024, ratio16 <= 4 * 65536: fits in 31 bits
  return scaled >= 0 ? scaled / 65536 : -((-scaled + 65535) / 65536);  // floor division
}

/// What a pixel of a selected disparity image holds besides its x16 value.
struct SelectedDisparity {
  ImageView<std::int16_t> disparity16;  ///< sub-pixel disparity x16, or kInvalidDisparity
  ImageView<std::int16_t> bestIndex;    ///< winner index d - minDisparity, or -1 if invalid
};

namespace cpu_ref {

/// Census transform (9x7 or centre-symmetric 9x7): one bit per comparison, window clamped at
/// the image border (border pixels repeat). Output bits are MSB-first in window raster order.
void censusTransform(ImageView<const std::uint8_t> image, CensusType type,
                     ImageView<std::uint64_t> census);
void censusTransform(ImageView<const std::uint16_t> image, CensusType type,
                     ImageView<std::uint64_t> census);

/// Stereo matching cost C_S(p, d): Hamming distance between the left census at p and the right
/// census at p - (minDisparity + d), for d in [0, numDisparities). Scaled to [0, kMaxCensusCost].
void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost);

/// Triple-SGM vertical matching cost C_V(p, d): Hamming distance between the left census at
/// p = (x, y) and the up census at (x, y + dv), dv = verticalDisparity(minDisparity + d, ratio16),
/// for d in [0, cost.numDisparities()). The up camera sits above the left one, so the scene appears
/// lower (larger y) in its image. Scaled as censusCost; kNoCounterpartCensusCost where y + dv
/// lies outside the up image.
void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost);

/// Triple-SGM camera cost C_S3 = (C_S + C_V + 1) >> 1: the rounded mean of the horizontal and
/// vertical census costs, in the same [0, kMaxCensusCost] range as C_S, so that alpha, P1, P2 and
/// lidarCostCap keep their meaning. C_S3 takes C_S's place in Eq. 5.
void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined);

/// LiDAR matching cost C_L(p, d) (Eq. 4): minimum over the points in p's pixel and its 8
/// neighbours of table(16*(minDisparity + d) - d_P16). Pixels no point touches cost 0 for
/// every d (no information). `support` (may be empty) is set to 1 where at least one point
/// touches the pixel, else 0.
void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity,
               MatchingCostVolume& cost, ImageView<std::uint8_t> support);

/// 1 where a LiDAR point lies within +-1 column and +-`rows` rows of the pixel, i.e. the pixel
/// is measured by the LiDAR or lies between two of its beams; else 0. The left-right check
/// spares these pixels in fused mode.
void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage);

/// Fused cost (Eq. 5): C = (w*C_L + (256-w)*C_S + 128) >> 8 with the pixel's LiDAR weight
/// w = weights(x, y) in [0, 256] (lidarWeights: alphaWeight(alpha) everywhere with a fixed alpha).
/// Where support is 0 and stereoCostWithoutLidar is set, C = C_S (the LiDAR knows nothing there).
void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, ImageView<const std::uint16_t> weights,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused);
/// The same with one weight for every pixel: exactly fuseCosts on a constant weight image.
void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, int alphaWeight256,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused);

/// SGM (Eq. 1) along 4 (left/right/up/down) or 8 (+ diagonal) paths; `sum` (resized to the
/// cost's size) receives the sum over paths.
void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths,
                    AggregatedCostVolume& sum);

/// Cost of one step of Eq. 1 for disparity d, given the previous pixel's path costs.
/// Exposed because it is the heart of SGM and is tested by hand.
int pathCostStep(int matchingCost, const std::uint16_t* previous, int numDisparities, int d,
                 int previousMin, int P1, int P2);

/// Winner-takes-all (Eq. 2) with optional uniqueness ratio and parabola sub-pixel fit.
void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio,
                     bool subpixel, SelectedDisparity out);

/// Right-view winner index for each right pixel xr: argmin_d sum(xr + minDisparity + d, d),
/// derived from the left volume (as OpenCV's SGBM does); -1 where no d maps inside the image.
void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity,
                         ImageView<std::int16_t> rightIndex);

/// Left-right consistency check on a selected disparity image (in place). A pixel is kept when
/// |leftIndex - rightIndex(x - d)| <= disp12MaxDiff, and never discarded when the LiDAR
/// covers it (support = 1, see lidarCoverage) or when it has no counterpart in the right image (x - d < 0):
/// the check cannot judge those. `keepNoCounterpart` = false (stereo-only) invalidates pixels
/// without counterpart instead, since nothing measured them (stereo-only has no LiDAR support).
void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                    bool keepNoCounterpart);

/// Confidence input 1, the shape of the aggregated cost curve at the winner b (the peak-ratio
/// margin): m = min(255, (256 * (S2 - S1)) / max(S2, 1)), S1 = S(b), S2 = min S(d) over |d - b| > 1
/// (outside the winner's own parabola). 0 = an ambiguous minimum (S2 = S1), 255 = no rival (also
/// when no d lies outside +-1). 0 where bestIndex is -1 (no winner). `bestCost` receives S1 (0
/// where there is no winner).
void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost);

/// Confidence input 2, left-right consistency: |bestIndex - rightIndex(x - minDisparity - best)|
/// capped at 254; kNoCounterpartDifference where the counterpart is outside the image, the right
/// view has no winner or the left pixel has none. Read before the left-right check invalidates.
void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference);

/// Median over the valid pixels of a size x size window (clamped at the border); invalid
/// pixels stay invalid. size 0 or 1 copies.
void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out);

}  // namespace cpu_ref
}  // namespace lidar_sgm
