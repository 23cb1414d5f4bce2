// SGM cost aggregation (Eq. 1) on the GPU.
//
// One warp walks one path line (a row, a column or a diagonal) from its start to its end; its 32
// lanes hold the path costs of the D disparities, VPL consecutive ones each (launch.cuh). A step
// needs the previous pixel's L at d - 1 and d + 1 (a shuffle across the lane boundary) and its
// minimum over d (a warp reduction). Every direction of a launch runs at once (blockIdx.y), each
// into its own L_r volume, so the rows, columns and diagonals of all directions keep the GPU
// busy; selection.cu sums them. The arithmetic is cpu_ref's pathCostStep, in int; the volumes
// store it in 8 bits where every path cost fits (pathCostsFit8Bits, as libSGM stores them: half
// the bytes written here and read by the selection), else in 16.
//
// A row is 1242 steps on KITTI and only 2 x 375 row lines run at once, so the time of a step's
// serial chain is the time of the stage. The matching cost is read from the volume stored before
// (cost_volume.cu), kAhead steps ahead of its use: the loads leave the chain, which keeps only
// the shuffles and the minimum.
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

// kPathDirections (backends/common/path_directions.hpp) in constant memory: the paper's four, then the diagonals.
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

/// How many steps ahead of its use a lane loads its matching costs and its pixel's window.
constexpr int kAhead = 4;

/// A lane's VPL matching costs (bytes) as one load: 1, 2 or 4 bytes in an unsigned, else 8 or 16.
template <int VPL>
struct CostWord {
  using type = unsigned;
};
template <>
struct CostWord<8> {
  using type = uint2;
};
template <>
struct CostWord<16> {
  using type = uint4;
};

/// What a step reads that does not depend on the recursion: its costs and its window.
template <int VPL>
struct StepInputs {
  typename CostWord<VPL>::type costs{};
  int windowFirst = 0;
  int windowEnd = 0;
};

/// The inputs of the pixel `step` steps along the line from (x0, y0); nothing past its end or for
/// a lane without disparities (its slots are never stored).
template <int VPL>
__device__ __forceinline__ StepInputs<VPL> loadStep(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows,
                                                    int x0, int y0, Direction r, int step, int length, int firstD,
                                                    bool active) {
  StepInputs<VPL> in;
  in.windowEnd = cost.numDisparities;
  if (step >= length) return in;
  const int x = x0 + step * r.dx;
  const int y = y0 + step * r.dy;
  if (!windows.empty()) {
    const std::size_t i = static_cast<std::size_t>(y) * cost.width + x;
    in.windowFirst = __ldg(windows.first + i);
    in.windowEnd = in.windowFirst + __ldg(windows.count + i);
  }
  if (!active) return in;
  const std::uint8_t* c = cost.at(x, y) + firstD;  // aligned: D is a multiple of 16, firstD of VPL
  if constexpr (VPL == 1) {
    in.costs = __ldg(c);
  } else if constexpr (VPL == 2) {
    in.costs = __ldg(reinterpret_cast<const unsigned short*>(c));
  } else if constexpr (VPL == 4) {
    in.costs = __ldg(reinterpret_cast<const unsigned*>(c));
  } else if constexpr (VPL == 8) {
    in.costs = __ldg(reinterpret_cast<const uint2*>(c));
  } else {
    in.costs = __ldg(reinterpret_cast<const uint4*>(c));
  }
  return in;
}

__device__ __forceinline__ int costByte(unsigned word, int k) { return static_cast<int>((word >> (8 * k)) & 0xFFu); }

/// The VPL costs of a load, as ints.
template <int VPL>
__device__ __forceinline__ void unpackCosts(const typename CostWord<VPL>::type& w, int (&c)[VPL]) {
  if constexpr (VPL <= 4) {
#pragma unroll
    for (int k = 0; k < VPL; ++k) c[k] = costByte(w, k);
  } else if constexpr (VPL == 8) {
#pragma unroll
    for (int k = 0; k < 4; ++k) {
      c[k] = costByte(w.x, k);
      c[k + 4] = costByte(w.y, k);
    }
  } else {
#pragma unroll
    for (int k = 0; k < 4; ++k) {
      c[k] = costByte(w.x, k);
      c[k + 4] = costByte(w.y, k);
      c[k + 8] = costByte(w.z, k);
      c[k + 12] = costByte(w.w, k);
    }
  }
}

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

/// The same in 8 bits (every value below 256: pathCostsFit8Bits): 1, 2 or 4 bytes in one store,
/// 8 or 16 as 4-byte words (aligned: the pixel's D bytes are a multiple of 16, firstD of VPL).
template <int VPL>
__device__ __forceinline__ void storeSlots(std::uint8_t* out, const int (&L)[VPL]) {
  if constexpr (VPL == 1) {
    out[0] = static_cast<std::uint8_t>(L[0]);
  } else if constexpr (VPL == 2) {
    *reinterpret_cast<unsigned short*>(out) =
        static_cast<unsigned short>(static_cast<unsigned>(L[0]) | (static_cast<unsigned>(L[1]) << 8));
  } else {
#pragma unroll
    for (int k = 0; k < VPL; k += 4) {
      *reinterpret_cast<unsigned*>(out + k) = static_cast<unsigned>(L[k]) | (static_cast<unsigned>(L[k + 1]) << 8) |
                                              (static_cast<unsigned>(L[k + 2]) << 16) |
                                              (static_cast<unsigned>(L[k + 3]) << 24);
    }
  }
}

template <int VPL, typename PathT>
__global__ void __launch_bounds__(kWarpsPerBlock * kWarpSize)
    aggregateKernel(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2,
                    DeviceVolume<PathT> pathCosts) {
  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const int line = static_cast<int>(blockIdx.x) * kWarpsPerBlock + static_cast<int>(threadIdx.x) / kWarpSize;
  const Direction r = kDirections[blockIdx.y];
  const int width = cost.width;
  const int D = cost.numDisparities;
  int x = 0;
  int y = 0;
  int length = 0;
  if (!pathLine(r, line, width, cost.height, x, y, length)) return;  // the whole warp leaves together

  const int firstD = lane * VPL;
  const bool active = firstD < D;  // all or none of a lane's slots are below D
  PathT* const volume = pathCosts.data + static_cast<std::size_t>(blockIdx.y) * pathCosts.size();
  // The next kAhead steps' inputs, in flight while the chain runs (kAhead == 4).
  const int x0 = x;
  const int y0 = y;
  StepInputs<VPL> ahead0 = loadStep<VPL>(cost, windows, x0, y0, r, 0, length, firstD, active);
  StepInputs<VPL> ahead1 = loadStep<VPL>(cost, windows, x0, y0, r, 1, length, firstD, active);
  StepInputs<VPL> ahead2 = loadStep<VPL>(cost, windows, x0, y0, r, 2, length, firstD, active);
  StepInputs<VPL> ahead3 = loadStep<VPL>(cost, windows, x0, y0, r, 3, length, firstD, active);
  static_assert(kAhead == 4, "the ring above holds kAhead steps");
  int previous[VPL];
  int previousMin = 0;
  for (int step = 0; step < length; ++step, x += r.dx, y += r.dy) {
    const StepInputs<VPL> now = ahead0;
    ahead0 = ahead1;
    ahead1 = ahead2;
    ahead2 = ahead3;
    ahead3 = loadStep<VPL>(cost, windows, x0, y0, r, step + kAhead, length, firstD, active);
    int L[VPL];
    int c[VPL];
    unpackCosts<VPL>(now.costs, c);  // zeros for a lane without disparities
    // This pixel's window (the whole range without the gate).
    const int windowFirst = now.windowFirst;
    const int windowEnd = now.windowEnd;
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
      for (int k = 0; k < VPL; ++k) stored[k] = L[k] == kAbsent ? absentPathCost<PathT>() : L[k];
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

template <typename PathT>
void launchAggregation(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2, int paths,
                       DeviceVolume<PathT> pathCosts, cudaStream_t stream) {
  const dim3 grid(
      static_cast<unsigned>((linesOf(cost.width, cost.height, paths) + kWarpsPerBlock - 1) / kWarpsPerBlock),
      static_cast<unsigned>(paths));
  withSlotsPerLane(cost.numDisparities, [&](auto slots) {
    constexpr int VPL = decltype(slots)::value;
    aggregateKernel<VPL, PathT><<<grid, kWarpsPerBlock * kWarpSize, 0, stream>>>(cost, windows, P1, P2, pathCosts);
  });
  LIDAR_SGM_CUDA_CHECK_LAUNCH("aggregateKernel");
}

}  // namespace

void aggregatePaths(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2, int paths,
                    DeviceVolume<std::uint8_t> pathCosts, cudaStream_t stream) {
  launchAggregation(cost, windows, P1, P2, paths, pathCosts, stream);
}

void aggregatePaths(DeviceVolume<const std::uint8_t> cost, DeviceWindows windows, int P1, int P2, int paths,
                    DeviceVolume<std::uint16_t> pathCosts, cudaStream_t stream) {
  launchAggregation(cost, windows, P1, P2, paths, pathCosts, stream);
}

}  // namespace cuda
}  // namespace lidar_sgm
