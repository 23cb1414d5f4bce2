#pragma once
/// @file kernels.hpp  The CUDA backend's stages as kernel launches on a stream, one .cu file per
/// stage (named as cpu_ref's). Inputs and outputs are device memory; nothing here copies or
/// synchronises. Each launch checks its own launch error.

#include <cstdint>

#include <cuda_runtime_api.h>

#include "backends/common/path_costs.hpp"
#include "backends/cuda/device_types.hpp"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace cuda {

// census.cu
void censusTransform(DeviceImage<const std::uint8_t> image, CensusType type, DeviceImage<std::uint64_t> census,
                     cudaStream_t stream);
void censusTransform(DeviceImage<const std::uint16_t> image, CensusType type, DeviceImage<std::uint64_t> census,
                     cudaStream_t stream);

// lidar_cost.cu: pixelStart[p] (p = 0 .. pixels) = the first of the `count` points (sorted by
// pixel, LidarPoints::pointPixels) whose pixel is >= p: LidarPoints' compressed rows.
void lidarPixelStarts(const int* pointPixels, int count, int pixels, int* pixelStart, cudaStream_t stream);
// lidar_cost.cu: 1 where a point lies in the pixel's 3x3 neighbourhood (C_L has information).
void lidarSupport(DeviceLidar lidar, DeviceImage<std::uint8_t> support, cudaStream_t stream);
/// 1 where a point lies within +-1 column and +-rows rows (the left-right check spares it).
void lidarCoverage(DeviceLidar lidar, int rows, DeviceImage<std::uint8_t> coverage, cudaStream_t stream);
// search_windows.cu: the LiDAR gate's windows (lidar_search_windows.hpp) of every pixel into
// first and count (W x H each), the host's bit for bit; lowest and highest (W x H each) are the
// first pass's scratch.
void lidarSearchWindows(DeviceLidar lidar, int minDisparity, int numDisparities, int rows, int margin,
                        DeviceImage<std::int16_t> lowest, DeviceImage<std::int16_t> highest,
                        DeviceImage<std::int16_t> first, DeviceImage<std::int16_t> count, cudaStream_t stream);

// cost_volume.cu: the matching cost as a volume, stored once per frame for the path recursion
// (CostPart::Matching); the parts alone let each cost be tested against cpu_ref's volume.
enum class CostPart {
  Census,          ///< C_S
  VerticalCensus,  ///< C_V (Triple-SGM)
  Lidar,           ///< C_L
  Matching,        ///< C as the matcher uses it (settings decide: C_S, C_S3, C_L or Eq. 5)
};
void matchingCostVolume(const CostSettings& settings, CostPart part, DeviceVolume<std::uint8_t> cost,
                        cudaStream_t stream);
/// C_S3 from stored C_S and C_V volumes (combineCameraCosts).
void combineCameraCosts(DeviceVolume<const std::uint8_t> horizontal, DeviceVolume<const std::uint8_t> vertical,
                        DeviceVolume<std::uint8_t> combined, cudaStream_t stream);
/// Eq. 5 from stored C_L and C_S volumes (fuseCosts): per-pixel weights, or alphaWeight if empty.
void fuseCosts(DeviceVolume<const std::uint8_t> lidar, DeviceVolume<const std::uint8_t> stereo,
               DeviceImage<const std::uint8_t> support, DeviceImage<const std::uint16_t> weights, int alphaWeight,
               bool stereoCostWithoutLidar, DeviceVolume<std::uint8_t> fused, cudaStream_t stream);

/// A path cost or sum outside its pixel's search window (the gated search): no candidate. Every
/// real value is below it (L <= 255 + P2, S <= 8 * (255 + 4000)), so the whole-range search never
/// stores it and the stages after the aggregation need no windows: they skip this value.
constexpr std::uint16_t kAbsentPathCost = 0xFFFF;
/// The same in an 8-bit L_r volume: path costs are stored in 8 bits only when every real one is
/// below it (pathCostsFit8Bits).
constexpr std::uint8_t kAbsentPathCost8 = 0xFF;

/// What an entry outside its pixel's window holds in an L_r volume of PathT (uint8 or uint16).
template <typename PathT>
LIDAR_SGM_HOST_DEVICE constexpr int absentPathCost() {
  return sizeof(PathT) == 1 ? kAbsentPathCost8 : kAbsentPathCost;
}

/// Whether a frame's L_r volumes hold 8 bits a path cost (as libSGM's): the largest path cost
/// (path_costs.hpp) below kAbsentPathCost8, which marks an entry outside a window. Half the
/// bytes written by the aggregation and read by the selection.
inline bool pathCostsFit8Bits(int maxCost, int P2) { return largestPathCost(maxCost, P2) < kAbsentPathCost8; }

// aggregation.cu: Eq. 1 along `paths` directions (cpu_ref's order) on a stored matching-cost
// volume, L_r of direction r into pathCosts + r * volume size, in 8 bits (only where
// pathCostsFit8Bits) or 16. With `windows` (the gated search), Eq. 1 runs on each pixel's window
// (gated_stages.hpp) and an entry outside it holds kAbsentPathCost8 / kAbsentPathCost; empty
// windows: the whole range.
void aggregatePaths(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2, int paths,
                    DeviceVolume<std::uint8_t> pathCosts, cudaStream_t stream);
void aggregatePaths(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2, int paths,
                    DeviceVolume<std::uint16_t> pathCosts, cudaStream_t stream);

// selection.cu: S = sum of the `numPaths` volumes at pathCosts (written to `sum` unless its data
// is null; kAbsentPathCost where the paths hold their absent value), then winner-takes-all with
// uniqueness and sub-pixel (Eq. 2) over the entries that are not absent, unless disparity16 is
// empty.
void selectDisparity(DeviceVolume<const std::uint8_t> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                     int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                     DeviceImage<std::int16_t> bestIndex, cudaStream_t stream);
void selectDisparity(DeviceVolume<const std::uint16_t> pathCosts, int numPaths, DeviceVolume<std::uint16_t> sum,
                     int minDisparity, int uniquenessRatio, bool subpixel, DeviceImage<std::int16_t> disparity16,
                     DeviceImage<std::int16_t> bestIndex, cudaStream_t stream);

// confidence_inputs.cu
void peakRatioMargin(DeviceVolume<const std::uint16_t> sum, DeviceImage<const std::int16_t> bestIndex,
                     DeviceImage<std::uint8_t> margin, DeviceImage<std::uint16_t> bestCost, cudaStream_t stream);
void leftRightDifference(DeviceImage<const std::int16_t> bestIndex, DeviceImage<const std::int16_t> rightIndex,
                         int minDisparity, DeviceImage<std::uint8_t> difference, cudaStream_t stream);

// confidence.cu: the core's part of the confidence (core/confidence_inputs.hpp) on the device.
/// `vertical` is scratch of the support's size.
void lidarDistance(DeviceImage<const std::uint8_t> support, DeviceImage<std::uint8_t> vertical,
                   DeviceImage<std::uint8_t> distance, cudaStream_t stream);
void textureAndSaturation(DeviceImage<const std::uint8_t> image, DeviceImage<std::uint8_t> texture,
                          DeviceImage<std::uint8_t> saturated, cudaStream_t stream);
void textureAndSaturation(DeviceImage<const std::uint16_t> image, DeviceImage<std::uint8_t> texture,
                          DeviceImage<std::uint8_t> saturated, cudaStream_t stream);
void disparityRange(DeviceImage<const std::int16_t> disparity, DeviceImage<std::uint8_t> range, cudaStream_t stream);
/// The seven inputs of a frame, on the device.
struct ConfidenceImages {
  DeviceImage<const std::uint8_t> margin;
  DeviceImage<const std::uint16_t> bestCost;
  DeviceImage<const std::uint8_t> leftRightDifference;
  DeviceImage<const std::uint8_t> lidarDistance;
  DeviceImage<const std::uint8_t> texture;
  DeviceImage<const std::uint8_t> saturated;
  DeviceImage<const std::uint8_t> disparityRange;
};
/// The logistic model of core/confidence.hpp; `sigmoidTable`: 2048 bytes, entry i =
/// confidenceFromLogit256(4 * (i - 1024)).
void combineConfidence(const ConfidenceImages& inputs, const ConfidenceModel& model, bool lidarOnly, int paths,
                       const std::uint8_t* sigmoidTable, DeviceImage<const std::int16_t> disparity,
                       DeviceImage<std::uint8_t> confidence, cudaStream_t stream);

// lr_check.cu
void rightDisparityIndex(DeviceVolume<const std::uint16_t> sum, int minDisparity,
                         DeviceImage<std::int16_t> rightIndex, cudaStream_t stream);
/// `support` may be empty (no LiDAR).
void leftRightCheck(DeviceImage<std::int16_t> disparity16, DeviceImage<std::int16_t> bestIndex,
                    DeviceImage<const std::int16_t> rightIndex, DeviceImage<const std::uint8_t> support,
                    int minDisparity, int disp12MaxDiff, bool keepNoCounterpart, cudaStream_t stream);

// median.cu
void medianFilter(DeviceImage<const std::int16_t> in, int size, DeviceImage<std::int16_t> out, cudaStream_t stream);

}  // namespace cuda
}  // namespace lidar_sgm
