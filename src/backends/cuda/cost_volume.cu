// The matching costs as stored volumes (cpu_ref's censusCost, verticalCensusCost, lidarCost,
// combineCameraCosts, fuseCosts). The matcher does not run these: its path recursion computes
// the same costs with the same functions (matching_cost.cuh). They let the tests compare each
// cost with cpu_ref's on its own, and so pin down what the recursion sees.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "backends/cuda/matching_cost.cuh"

namespace lidar_sgm {
namespace cuda {
namespace {

__global__ void costVolumeKernel(CostSettings s, CostPart part, DeviceVolume<std::uint8_t> cost) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= s.width || y >= s.height) return;
  const PixelCostContext c = pixelCostContext(s, x, y);
  std::uint8_t* out = cost.at(x, y);
  for (int d = 0; d < s.numDisparities; ++d) {
    const int disparity = s.minDisparity + d;
    int value = 0;
    switch (part) {
      case CostPart::Census: value = censusCostAt(c.leftBits, s.rightCensus, x, y, disparity, s.censusScale); break;
      case CostPart::VerticalCensus:
        value = verticalCensusCostAt(c.leftBits, s.upCensus, x, y, disparity, s.ratio16, s.censusScale);
        break;
      case CostPart::Lidar: value = lidarCostAt(s.lidar, s.table, c.lidar, disparity); break;
      case CostPart::Matching: value = matchingCost(s, c, x, y, d); break;
    }
    out[d] = static_cast<std::uint8_t>(value);
  }
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
  costVolumeKernel<<<pixelGrid(settings.width, settings.height), pixelBlock(), 0, stream>>>(settings, part, cost);
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
