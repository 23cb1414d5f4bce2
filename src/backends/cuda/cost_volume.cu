// The matching costs as stored volumes (cpu_ref's censusCost, verticalCensusCost, lidarCost,
// combineCameraCosts, fuseCosts). The matcher stores C (CostPart::Matching) once per frame and
// the path recursion (aggregation.cu) reads it: computed inside the recursion, the LiDAR term
// (Eq. 4, a walk over the 3x3 neighbourhood's points per disparity) was paid once per path and
// its loads sat on the recursion's serial chain. The parts alone (C_S, C_V, C_L) let the tests
// compare each cost with cpu_ref's.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "backends/cuda/matching_cost.cuh"

namespace lidar_sgm {
namespace cuda {
namespace {

constexpr int kPixelsPerBlock = 4;

/// Stores a lane's VPL costs (bytes) with one store: the pixel's D bytes are a multiple of 16 and
/// the lane's first byte is a multiple of VPL, so the store is aligned.
template <int VPL>
__device__ __forceinline__ void storeCostBytes(std::uint8_t* out, const int (&c)[VPL]) {
  if constexpr (VPL == 1) {
    out[0] = static_cast<std::uint8_t>(c[0]);
  } else if constexpr (VPL == 2) {
    *reinterpret_cast<unsigned short*>(out) = static_cast<unsigned short>(c[0] | (c[1] << 8));
  } else {
    unsigned words[VPL / 4];
#pragma unroll
    for (int w = 0; w < VPL / 4; ++w) {
      words[w] = static_cast<unsigned>(c[4 * w]) | (static_cast<unsigned>(c[4 * w + 1]) << 8) |
                 (static_cast<unsigned>(c[4 * w + 2]) << 16) | (static_cast<unsigned>(c[4 * w + 3]) << 24);
    }
    if constexpr (VPL == 4) {
      *reinterpret_cast<unsigned*>(out) = words[0];
    } else if constexpr (VPL == 8) {
      *reinterpret_cast<uint2*>(out) = make_uint2(words[0], words[1]);
    } else {
      *reinterpret_cast<uint4*>(out) = make_uint4(words[0], words[1], words[2], words[3]);
      *reinterpret_cast<uint4*>(out + 16) = make_uint4(words[4], words[5], words[6], words[7]);
    }
  }
}

/// One warp per pixel, VPL consecutive disparities a lane (the recursion's layout): the pixel's
/// context (census string, LiDAR neighbourhood, weight) is one broadcast load per warp, the right
/// census strings of consecutive disparities are consecutive words, and the warp stores the
/// pixel's D bytes at once.
template <int VPL>
__global__ void __launch_bounds__(kPixelsPerBlock * kWarpSize)
    costVolumeKernel(CostSettings s, CostPart part, DeviceVolume<std::uint8_t> cost) {
  const int lane = static_cast<int>(threadIdx.x) & (kWarpSize - 1);
  const std::size_t pixel =
      static_cast<std::size_t>(blockIdx.x) * kPixelsPerBlock + static_cast<std::size_t>(threadIdx.x) / kWarpSize;
  const int firstD = lane * VPL;
  if (pixel >= cost.pixels() || firstD >= s.numDisparities) return;  // all or none of a lane's slots are below D
  const int x = static_cast<int>(pixel % static_cast<std::size_t>(s.width));
  const int y = static_cast<int>(pixel / static_cast<std::size_t>(s.width));
  const PixelCostContext c = pixelCostContext(s, x, y);
  int values[VPL];
#pragma unroll
  for (int k = 0; k < VPL; ++k) {
    const int d = firstD + k;
    const int disparity = s.minDisparity + d;
    switch (part) {
      case CostPart::Census: values[k] = censusCostAt(c.leftBits, s.rightCensus, x, y, disparity, s.censusScale); break;
      case CostPart::VerticalCensus:
        values[k] = verticalCensusCostAt(c.leftBits, s.upCensus, x, y, disparity, s.ratio16, s.censusScale);
        break;
      case CostPart::Lidar: values[k] = lidarCostAt(s.lidar, s.table, c.lidar, disparity); break;
      default: values[k] = matchingCost(s, c, x, y, d); break;
    }
  }
  storeCostBytes<VPL>(cost.at(x, y) + firstD, values);
}

__global__ void combineKernel(DeviceVolume<const std::uint8_t> horizontal, DeviceVolume<const std::uint8_t> vertical,
                              DeviceVolume<std::uint8_t> combined) {
  const std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= combined.size()) return;
  combined.data[i] = static_cast<std::uint8_t>(combinedCameraCost(horizontal.data[i], vertical.data[i]));
}

__global__ void fuseKernel(DeviceVolume<const std::uint8_t> lidar, DeviceVolume<const std::uint8_t> stereo,
                           DeviceImage<const std::uint8_t> support, DeviceImage<const std::uint16_t> weights,
                           int alphaWeight, bool stereoCostWithoutLidar, DeviceVolume<std::uint8_t> fused) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= fused.width || y >= fused.height) return;
  const bool stereoOnlyHere = stereoCostWithoutLidar && support(x, y) == 0;
  const int w = weights.empty() ? alphaWeight : static_cast<int>(weights(x, y));
  const std::uint8_t* cL = lidar.at(x, y);
  const std::uint8_t* cS = stereo.at(x, y);
  std::uint8_t* out = fused.at(x, y);
  for (int d = 0; d < fused.numDisparities; ++d) {
    out[d] = static_cast<std::uint8_t>(fusedCost(cL[d], cS[d], w, stereoOnlyHere));
  }
}

}  // namespace

void matchingCostVolume(const CostSettings& settings, CostPart part, DeviceVolume<std::uint8_t> cost,
                        cudaStream_t stream) {
  const unsigned blocks = static_cast<unsigned>((cost.pixels() + kPixelsPerBlock - 1) / kPixelsPerBlock);
  withSlotsPerLane(settings.numDisparities, [&](auto slots) {
    constexpr int VPL = decltype(slots)::value;
    costVolumeKernel<VPL><<<blocks, kPixelsPerBlock * kWarpSize, 0, stream>>>(settings, part, cost);
  });
  LIDAR_SGM_CUDA_CHECK_LAUNCH("costVolumeKernel");
}

void combineCameraCosts(DeviceVolume<const std::uint8_t> horizontal, DeviceVolume<const std::uint8_t> vertical,
                        DeviceVolume<std::uint8_t> combined, cudaStream_t stream) {
  const unsigned blocks = static_cast<unsigned>((combined.size() + 255) / 256);
  combineKernel<<<blocks, 256, 0, stream>>>(horizontal, vertical, combined);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("combineKernel");
}

void fuseCosts(DeviceVolume<const std::uint8_t> lidar, DeviceVolume<const std::uint8_t> stereo,
               DeviceImage<const std::uint8_t> support, DeviceImage<const std::uint16_t> weights, int alphaWeight,
               bool stereoCostWithoutLidar, DeviceVolume<std::uint8_t> fused, cudaStream_t stream) {
  fuseKernel<<<pixelGrid(fused.width, fused.height), pixelBlock(), 0, stream>>>(
      lidar, stereo, support, weights, alphaWeight, stereoCostWithoutLidar, fused);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("fuseKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
