#pragma once
/// @file matching_cost.cuh  The matching cost C(p, d) on the GPU, one disparity at a time, with
/// the integer arithmetic of cpu_ref's stages (census_cost.cpp, vertical_census_cost.cpp,
/// combine_camera_costs.cpp, lidar_cost.cpp, fusion.cpp). cost_volume.cu stores C with them once
/// per frame for the path recursion (aggregation.cu), and each term alone for the stage tests.

#include <cstdint>

#include "backends/common/stages.hpp"
#include "backends/cuda/device_types.hpp"

namespace lidar_sgm {
namespace cuda {

/// C_S: Hamming distance of the left census at (x, y) and the right one at x - d (d: the absolute
/// disparity minDisparity + index), kNoCounterpartCensusCost where x - d leaves the image.
__device__ __forceinline__ int censusCostAt(std::uint64_t leftBits, DeviceImage<const std::uint64_t> right, int x,
                                            int y, int disparity, int scale) {
  const int xr = x - disparity;
  if (xr < 0 || xr >= right.width) return kNoCounterpartCensusCost;
  return scale * __popcll(leftBits ^ __ldg(right.row(y) + xr));
}

/// C_V (Triple-SGM): against the up census at y + verticalDisparity(d), kNoCounterpartCensusCost
/// where that row leaves the image.
__device__ __forceinline__ int verticalCensusCostAt(std::uint64_t leftBits, DeviceImage<const std::uint64_t> up,
                                                    int x, int y, int disparity, int ratio16, int scale) {
  const int yu = y + verticalDisparity(disparity, ratio16);
  if (yu < 0 || yu >= up.height) return kNoCounterpartCensusCost;
  return scale * __popcll(leftBits ^ __ldg(up.row(yu) + x));
}

/// C_S3 = (C_S + C_V + 1) >> 1, the rounded mean.
__device__ __forceinline__ int combinedCameraCost(int horizontal, int vertical) { return (horizontal + vertical + 1) >> 1; }

/// One entry of the LiDAR cost table: min(cap, round(64/sigma^2 diff^2)) for diff in 1/16 px.
__device__ __forceinline__ int lidarTableCost(DeviceCostTable table, int diff16) {
  const int k = diff16 < 0 ? -diff16 : diff16;
  return k < table.size ? static_cast<int>(__ldg(table.entries + k)) : table.cap;
}

/// The LiDAR points associated with pixel (x, y): those of the pixel and its 8 neighbours, as
/// three runs of the compressed rows (one per image row: the 3 columns of a row are adjacent).
struct LidarNeighbourhood {
  int begin[3];
  int end[3];
  int rows = 0;
  __device__ bool empty() const {
    for (int i = 0; i < rows; ++i) {
      if (end[i] > begin[i]) return false;
    }
    return true;
  }
};

__device__ __forceinline__ LidarNeighbourhood lidarNeighbourhood(DeviceLidar lidar, int x, int y) {
  LidarNeighbourhood n;
  const int x0 = x > 0 ? x - 1 : 0;
  const int x1 = x + 1 < lidar.width ? x + 1 : lidar.width - 1;
  for (int ny = y > 0 ? y - 1 : 0; ny <= y + 1 && ny < lidar.height; ++ny) {
    const int* rowStart = lidar.pixelStart + static_cast<std::size_t>(ny) * lidar.width;
    n.begin[n.rows] = __ldg(rowStart + x0);
    n.end[n.rows] = __ldg(rowStart + x1 + 1);
    ++n.rows;
  }
  return n;
}

/// C_L (Eq. 4): the minimum over the associated points of table(16 d - d_P), 0 without points.
__device__ __forceinline__ int lidarCostAt(DeviceLidar lidar, DeviceCostTable table, const LidarNeighbourhood& n,
                                           int disparity) {
  if (n.empty()) return 0;  // no information: the same cost for every disparity
  const int disparity16 = disparity * kDisparityScale;
  int best = table.cap;
  for (int i = 0; i < n.rows; ++i) {
    for (int j = n.begin[i]; j < n.end[i]; ++j) {
      const int c = lidarTableCost(table, disparity16 - __ldg(lidar.disparities16 + j));
      best = c < best ? c : best;
    }
  }
  return best;
}

/// Eq. 5: (w C_L + (256 - w) C_S + 128) >> 8, or C_S alone where the LiDAR is blind and
/// stereoCostWithoutLidar asks for it.
__device__ __forceinline__ int fusedCost(int lidarCost, int cameraCost, int weight, bool stereoOnlyHere) {
  return stereoOnlyHere ? cameraCost : (weight * lidarCost + (256 - weight) * cameraCost + 128) >> 8;
}

/// What a pixel's costs need once, before its disparities: its census, LiDAR neighbourhood and weight.
struct PixelCostContext {
  std::uint64_t leftBits = 0;
  LidarNeighbourhood lidar;
  bool supported = false;
  int weight = 0;
};

__device__ __forceinline__ PixelCostContext pixelCostContext(const CostSettings& s, int x, int y) {
  PixelCostContext c;
  if (s.useCamera) c.leftBits = __ldg(s.leftCensus.row(y) + x);
  if (s.useLidar) {
    c.lidar = lidarNeighbourhood(s.lidar, x, y);
    c.supported = !c.lidar.empty();
    c.weight = s.weights.empty() ? s.alphaWeight : static_cast<int>(__ldg(s.weights.row(y) + x));
  }
  return c;
}

/// C(p, d) for the disparity index d (absolute disparity minDisparity + d), as cpu_ref's stages
/// produce it: C_S (or C_S3) stereo-only, C_L LiDAR-only, Eq. 5 fused.
__device__ __forceinline__ int matchingCost(const CostSettings& s, const PixelCostContext& c, int x, int y, int d) {
  const int disparity = s.minDisparity + d;
  int camera = 0;
  if (s.useCamera) {
    camera = censusCostAt(c.leftBits, s.rightCensus, x, y, disparity, s.censusScale);
    if (!s.upCensus.empty()) {
      camera = combinedCameraCost(camera,
                                  verticalCensusCostAt(c.leftBits, s.upCensus, x, y, disparity, s.ratio16, s.censusScale));
    }
    if (!s.useLidar) return camera;
  }
  const int lidar = lidarCostAt(s.lidar, s.table, c.lidar, disparity);
  if (!s.useCamera) return lidar;
  return fusedCost(lidar, camera, c.weight, s.stereoCostWithoutLidar && !c.supported);
}

}  // namespace cuda
}  // namespace lidar_sgm
