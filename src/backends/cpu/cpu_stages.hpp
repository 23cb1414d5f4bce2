#pragma once
// The fast CPU backend's stages: the signatures of cpu_ref's (backends/common/stages.hpp) plus
// the number of worker threads. Each one is bit-identical to its cpu_ref twin for any `threads`
// (fixed partitions of rows or columns; no reduction whose order depends on the thread count).
//
// SIMD comes from Highway with runtime dispatch (the same binary runs AVX-512, AVX2, SSE4 or
// NEON code, whichever the CPU has); threads from OpenMP. The matcher (cpu_matcher.hpp) streams
// the same row kernels (cpu_kernels.hpp) with only one volume (the fused cost) and no C_S, C_L or
// path-cost volumes; these whole-volume stages exist so that every stage can be tested against
// cpu_ref on its own.

#include <cstdint>
#include <vector>

#include "backends/common/search_windows.hpp"
#include "backends/common/stages.hpp"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace cpu {

void censusTransform(ImageView<const std::uint8_t> image, CensusType type, ImageView<std::uint64_t> census,
                     int threads);
void censusTransform(ImageView<const std::uint16_t> image, CensusType type, ImageView<std::uint64_t> census,
                     int threads);

void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost, int threads);

void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost, int threads);

void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined, int threads);

void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity, MatchingCostVolume& cost,
               ImageView<std::uint8_t> support, int threads);

void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage, int threads);

/// The LiDAR gate's windows (lidar_search_windows.hpp), its two passes on `threads` threads.
void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows, int threads);

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, int alphaWeight256, bool stereoCostWithoutLidar,
               MatchingCostVolume& fused, int threads);
void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo,
               ImageView<const std::uint8_t> support, ImageView<const std::uint16_t> weights,
               bool stereoCostWithoutLidar, MatchingCostVolume& fused, int threads);

void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum,
                    int threads);

void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out, int threads);

void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity, ImageView<std::int16_t> rightIndex,
                         int threads);

void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff,
                    bool keepNoCounterpart, int threads);

void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost, int threads);

void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference, int threads);

void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out, int threads);

// The confidence's core part (confidence.cpp): the core's functions of core/confidence_inputs.hpp,
// which cpu_ref runs, plus the thread count; the same bytes for any `threads`.

/// Whole-image buffers of the functions below, kept by the matcher between frames (grown only).
struct ConfidenceBuffers {
  std::vector<std::uint8_t> vertical;  ///< the LiDAR distance along columns
  std::vector<std::uint8_t> gradient;  ///< |I(x+1) - I(x-1)|, two repeated border columns each side
  std::vector<std::uint16_t> rowSum;   ///< its sum over 5 columns
  std::vector<std::int16_t> rowMin, rowMax;  ///< the valid disparities' extremes over 5 columns
};

void lidarDistance(ImageView<const std::uint8_t> support, ImageView<std::uint8_t> distance,
                   ConfidenceBuffers& buffers, int threads);
void textureAndSaturation(const GrayImageView& image, ImageView<std::uint8_t> texture,
                          ImageView<std::uint8_t> saturated, ConfidenceBuffers& buffers, int threads);
void disparityRange(ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> range,
                    ConfidenceBuffers& buffers, int threads);
void combineConfidence(const ConfidenceInputs& inputs, MatchMode mode, int paths,
                       ImageView<const std::int16_t> disparity, ImageView<std::uint8_t> confidence, int threads);
/// All four above in one pass of one thread team (what the matcher runs): `inputs`' lidarDistance,
/// texture, saturated and disparityRange, then `confidence`, all already at the disparity's size;
/// their margin, bestCost and leftRightDifference already filled. An empty `image`: t = s = 0.
void confidenceOfFrame(const GrayImageView& image, ImageView<const std::uint8_t> support,
                       ImageView<const std::int16_t> disparity, MatchMode mode, int paths, ConfidenceInputs& inputs,
                       ImageView<std::uint8_t> confidence, ConfidenceBuffers& buffers, int threads);

}  // namespace cpu
}  // namespace lidar_sgm
