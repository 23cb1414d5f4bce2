// SGM cost aggregation (Eq. 1) on the GPU.
//
// One warp walks one path line (a row, a column or a diagonal) from its start to its end; its 32
// lanes hold the path costs of the D disparities, VPL consecutive ones each (launch.cuh). A step
// needs the previous pixel's L at d - 1 and d + 1 (a shuffle across the lane boundary) and its
// minimum over d (a warp reduction). Every direction of a launch runs at once (blockIdx.y), each
// into its own L_r volume, so the rows, columns and diagonals of all directions keep the GPU
// busy; selection.cu sums them. The arithmetic is cpu_ref's pathCostStep, in int.
//
// The gated search (gated_stages.hpp): a disparity outside the pixel's window holds kAbsent in the
// lane's registers, so that the next step's terms from it (L(p-r, d), L(p-r, d+-1) + P1) never
// win against min_k L(p-r, k) + P2, which is always present, and the warp's minimum is the
// window's; it is stored as kAbsentPathCost. Without windows every disparity is in the window and
// the step is Eq. 1 as before.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "backends/cuda/matching_cost.cuh"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kWarpsPerBlock = 4;
/// A path cost outside the window, in registers: above every real one and every sum of one with P1.
constexpr int kAbsent = 1 << 24;

struct Direction {
  int dx;
  int dy;
};

// cpu_ref's order (aggregation.cpp): the paper's four, then the diagonals.
__constant__ Direction kDirections[8] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

/// The first pixel of path line `line` of direction r and its length; false past the last line.
/// Every line starts where the previous pixel (x - dx, y - dy) lies outside the image, so
/// L_r = C there, as in cpu_ref; together the lines of a direction visit every pixel once.
__device__ bool pathLine(Direction r, int line, int width, int height, int& x, int& y, int& length) {
  if (r.dy == 0) {  // rows
    if (line >= height) return false;
    x = r.dx > 0 ? 0 : width - 1;
    y = line;
    length = width;
    return true;
  }
  if (r.dx == 0) {  // columns
    if (line >= width) return false;
    x = line;
    y = r.dy > 0 ? 0 : height - 1;
    length = height;
    return true;
  }
  // Diagonals: one from each pixel of the first row (in the direction of travel), then one
  // from each other pixel of the first column.
  if (line >= width + height - 1) return false;
  if (line < width) {
    x = line;
    y = r.dy > 0 ? 0 : height - 1;
  } else {
    const int j = line - width + 1;
    x = r.dx > 0 ? 0 : width - 1;
    y = r.dy > 0 ? j : height - 1 - j;
  }
  const int alongX = r.dx > 0 ? width - x : x + 1;
  const int alongY = r.dy > 0 ? height - y : y + 1;
  length = min(alongX, alongY);
  return true;
}

/// The matching cost computed in the recursion from census strings and LiDAR points.
struct ComputedCost {
  CostSettings s;
  template <int VPL>
  __device__ void operator()(int x, int y, int firstD, int (&cost)[VPL]) const {
    const PixelCostContext c = pixelCostContext(s, x, y);
#pragma unroll
    for (int k = 0; k < VPL; ++k) cost[k] = matchingCost(s, c, x, y, firstD + k);
  }
};

/// A stored matching-cost volume (the stage test's input).
struct StoredCost {
  DeviceVolume<const std::uint8_t> volume;
  template <int VPL>
  __device__ void operator()(int x, int y, int firstD, int (&cost)[VPL]) const {
    const std::uint8_t* c = volume.at(x, y) + firstD;
#pragma unroll
    for (int k = 0; k < VPL; ++k) cost[k] = __ldg(c + k);
  }
};

/// Stores a lane's VPL path costs (uint16) with one vector store where the width allows.
template <int VPL>
__device__ __forceinline__ void storeSlots(std::uint16_t* out, const int (&L)[VPL]) {
  if constexpr (VPL == 1) {
    out[0] = static_cast<std::uint16_t>(L[0]);
  } else if constexpr (VPL == 2) {
    *reinterpret_cast<unsigned*>(out) = static_cast<unsigned>(L[0]) | (static_cast<unsigned>(L[1]) << 16);
  } else {
    // VPL >= 4: 8, 16 or 32 bytes, aligned (the pixel's D * 2 bytes are a multiple of 32).
#pragma unroll
    for (int k = 0; k < VPL; k += 4) {
      uint2 v;
      v.x = static_cast<unsigned>(L[k]) | (static_cast<unsigned>(L[k + 1]) << 16);
      v.y = static_cast<unsigned>(L[k + 2]) | (static_cast<unsigned>(L[k + 3]) << 16);
      *reinterpret_cast<uint2*>(out + k) = v;
    }
  }
}

template <int VPL, typename Cost>
__global__ void __launch_bounds__(kWarpsPerBlock * kWarpSize)
    aggregateKernel(Cost cost, DeviceWindows windows, int width, int height, int D, int P1, int P2,
                    DeviceVolume<std::uint16_t> pathCosts) {
  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const int line = static_cast<int>(blockIdx.x) * kWarpsPerBlock + static_cast<int>(threadIdx.x) / kWarpSize;
  const Direction r = kDirections[blockIdx.y];
  int x = 0;
  int y = 0;
  int length = 0;
  if (!pathLine(r, line, width, height, x, y, length)) return;  // the whole warp leaves together

  const int firstD = lane * VPL;
  const bool active = firstD < D;  // all or none of a lane's slots are below D
  std::uint16_t* const volume = pathCosts.data + static_cast<std::size_t>(blockIdx.y) * pathCosts.size();
  int previous[VPL];
  int previousMin = 0;
  for (int step = 0; step < length; ++step, x += r.dx, y += r.dy) {
    int L[VPL];
    int c[VPL];
    // This pixel's window (the whole range without the gate).
    int windowFirst = 0;
    int windowEnd = D;
    if (!windows.empty()) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      windowFirst = windows.first[i];
      windowEnd = windowFirst + windows.count[i];
    }
    if (active) {
      cost(x, y, firstD, c);
    } else {
#pragma unroll
      for (int k = 0; k < VPL; ++k) c[k] = 0;
    }
    if (step == 0) {
      // The path starts here: L_r(p, d) = C(p, d).
#pragma unroll
      for (int k = 0; k < VPL; ++k) {
        const int d = firstD + k;
        L[k] = d >= windowFirst && d < windowEnd ? c[k] : kAbsent;
      }
    } else {
      // Eq. 1: C(p,d) + min(L(p-r,d), L(p-r,d-1)+P1, L(p-r,d+1)+P1, min_i L(p-r,i)+P2) - min_k L(p-r,k).
      const int fromLeftLane = __shfl_up_sync(kFullMask, previous[VPL - 1], 1);
      const int fromRightLane = __shfl_down_sync(kFullMask, previous[0], 1);
#pragma unroll
      for (int k = 0; k < VPL; ++k) {
        const int d = firstD + k;
        int best = previous[k];
        if (d > 0) best = min(best, (k > 0 ? previous[k - 1] : fromLeftLane) + P1);
        if (d + 1 < D) best = min(best, (k + 1 < VPL ? previous[k + 1] : fromRightLane) + P1);
        best = min(best, previousMin + P2);
        L[k] = d >= windowFirst && d < windowEnd ? c[k] + best - previousMin : kAbsent;
      }
    }
    int laneMin = INT_MAX;
    if (active) {
#pragma unroll
      for (int k = 0; k < VPL; ++k) laneMin = min(laneMin, L[k]);
      int stored[VPL];
#pragma unroll
      for (int k = 0; k < VPL; ++k) stored[k] = L[k] == kAbsent ? kAbsentPathCost : L[k];
      storeSlots<VPL>(volume + (static_cast<std::size_t>(y) * width + x) * D + firstD, stored);
    }
    previousMin = warpMin(laneMin);
#pragma unroll
    for (int k = 0; k < VPL; ++k) previous[k] = L[k];
  }
}

int linesOf(int width, int height, int paths) {
  // Rows, columns, and with 8 paths the diagonals (width + height - 1 lines each).
  int lines = width > height ? width : height;
  if (paths == 8 && width + height - 1 > lines) lines = width + height - 1;
  return lines;
}

template <typename Cost>
void launchAggregation(const Cost& cost, DeviceWindows windows, int width, int height, int D, int P1, int P2,
                       int paths, DeviceVolume<std::uint16_t> pathCosts, cudaStream_t stream) {
  const dim3 grid(static_cast<unsigned>((linesOf(width, height, paths) + kWarpsPerBlock - 1) / kWarpsPerBlock),
                  static_cast<unsigned>(paths));
  withSlotsPerLane(D, [&](auto slots) {
    constexpr int VPL = decltype(slots)::value;
    aggregateKernel<VPL, Cost><<<grid, kWarpsPerBlock * kWarpSize, 0, stream>>>(cost, windows, width, height, D, P1,
                                                                                P2, pathCosts);
  });
  LIDAR_SGM_CUDA_CHECK_LAUNCH("aggregateKernel");
}

}  // namespace

void aggregatePaths(const CostSettings& settings, DeviceWindows windows, int P1, int P2, int paths,
                    DeviceVolume<std::uint16_t> pathCosts, cudaStream_t stream) {
  launchAggregation(ComputedCost{settings}, windows, settings.width, settings.height, settings.numDisparities, P1, P2,
                    paths, pathCosts, stream);
}

void aggregatePaths(DeviceVolume<const std::uint8_t> cost, int P1, int P2, int paths,
                    DeviceVolume<std::uint16_t> pathCosts, cudaStream_t stream) {
  launchAggregation(StoredCost{cost}, DeviceWindows{}, cost.width, cost.height, cost.numDisparities, P1, P2, paths,
                    pathCosts, stream);
}

}  // namespace cuda
}  // namespace lidar_sgm
