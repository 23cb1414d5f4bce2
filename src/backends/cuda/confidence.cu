// The core's part of the confidence (core/confidence_inputs.cpp, core/confidence.cpp) on the GPU,
// so that a frame's confidence never leaves the device: the distance to the nearest LiDAR
// support, texture and saturation, the local disparity range, and the logistic combination. Each
// kernel computes the same integers as the core's host code (the same separable passes where
// their order matters, direct window sums where it does not), and the logistic curve is the
// core's own table (confidenceFromLogit256), copied to the device once.
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/launch.cuh"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

// Per column: the distance [rows] to the nearest support in that column, capped (two sweeps).
__global__ void verticalDistanceKernel(DeviceImage<const std::uint8_t> support, DeviceImage<std::uint8_t> vertical) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  if (x >= support.width) return;
  const int cap = kLidarDistanceCap;
  int carried = cap;
  for (int y = 0; y < support.height; ++y) {
    carried = support(x, y) != 0 ? 0 : min(carried + 1, cap);
    vertical(x, y) = static_cast<std::uint8_t>(carried);
  }
  carried = cap;
  for (int y = support.height - 1; y >= 0; --y) {
    const int v = min(static_cast<int>(vertical(x, y)), min(carried + 1, cap));
    vertical(x, y) = static_cast<std::uint8_t>(v);
    carried = v;
  }
}

// Chebyshev: min over |dx| < best of max(|dx|, vertical(x + dx)).
__global__ void lidarDistanceKernel(DeviceImage<const std::uint8_t> vertical, DeviceImage<std::uint8_t> distance) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= vertical.width || y >= vertical.height) return;
  int best = vertical(x, y);
  for (int dx = 1; dx < best; ++dx) {
    if (x - dx >= 0) best = min(best, max(dx, static_cast<int>(vertical(x - dx, y))));
    if (x + dx < vertical.width) best = min(best, max(dx, static_cast<int>(vertical(x + dx, y))));
  }
  distance(x, y) = static_cast<std::uint8_t>(best);
}

// |I(x+1) - I(x-1)| >> shift, border pixels repeating.
template <typename Pixel>
__device__ __forceinline__ int gradientAt(DeviceImage<const Pixel> image, int x, int y, int shift) {
  const int a = image(min(x + 1, image.width - 1), y);
  const int b = image(max(x - 1, 0), y);
  return abs(a - b) >> shift;
}

template <typename Pixel>
__global__ void textureKernel(DeviceImage<const Pixel> image, int shift, int saturation,
                              DeviceImage<std::uint8_t> texture, DeviceImage<std::uint8_t> saturated) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= image.width || y >= image.height) return;
  // The 5x5 sum of gradients, the window clamped at the border (border gradients repeat).
  int sum = 0;
  for (int dy = -2; dy <= 2; ++dy) {
    const int ny = min(max(y + dy, 0), image.height - 1);
    for (int dx = -2; dx <= 2; ++dx) sum += gradientAt(image, min(max(x + dx, 0), image.width - 1), ny, shift);
  }
  texture(x, y) = static_cast<std::uint8_t>(min((sum + 12) / 25, 255));
  saturated(x, y) = static_cast<int>(image(x, y)) >= saturation ? 1 : 0;
}

// max - min of the valid disparities in the 5x5 window (the window cut at the border) [px].
__global__ void disparityRangeKernel(DeviceImage<const std::int16_t> disparity, DeviceImage<std::uint8_t> range) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= disparity.width || y >= disparity.height) return;
  if (disparity(x, y) == kInvalidDisparity) {
    range(x, y) = 0;
    return;
  }
  int lo = disparity(x, y);
  int hi = lo;
  for (int ny = max(0, y - 2); ny <= min(disparity.height - 1, y + 2); ++ny) {
    for (int nx = max(0, x - 2); nx <= min(disparity.width - 1, x + 2); ++nx) {
      const int d = disparity(nx, ny);
      if (d == kInvalidDisparity) continue;
      lo = min(lo, d);
      hi = max(hi, d);
    }
  }
  range(x, y) = static_cast<std::uint8_t>(min((hi - lo) / kDisparityScale, kDisparityRangeCap));
}


// confidencePixel, confidenceLogit256 and confidenceFromLogit256 (core/confidence.cpp).
__global__ void combineKernel(ConfidenceImages in, ConfidenceModel model, bool lidarOnly, int paths,
                              const std::uint8_t* sigmoid, DeviceImage<const std::int16_t> disparity,
                              DeviceImage<std::uint8_t> confidence) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= disparity.width || y >= disparity.height) return;
  if (disparity(x, y) == kInvalidDisparity) {
    confidence(x, y) = 0;
    return;
  }
  const int m = in.margin(x, y);
  const int c = min(static_cast<int>(in.bestCost(x, y)) / paths, 255);
  const int leftRight = lidarOnly ? 0 : in.leftRightDifference(x, y);
  const int g = in.lidarDistance(x, y);
  const int t = lidarOnly ? 0 : in.texture(x, y);
  const int s = lidarOnly ? 0 : in.saturated(x, y);
  const int v = in.disparityRange(x, y);
  const int n = leftRight == kNoCounterpartDifference ? 1 : 0;
  const int r = n != 0 ? 0 : min(leftRight, kLeftRightDifferenceCap);
  const int logit = model.bias + model.margin * m + model.marginLow * min(m, 16) + model.cost * c +
                    model.leftRight * r + model.noCounterpart * n + model.lidarDistance * g +
                    model.lidarDistanceLow * min(g, 4) + model.texture * t + model.textureLow * min(t, 8) +
                    model.saturated * s + model.disparityRange * v + model.disparityRangeLow * min(v, 2);
  const int z64 = min(max(logit, -4096), 4095) >> 2;  // floor division by 4, also below zero
  confidence(x, y) = sigmoid[z64 + 1024];
}

}  // namespace

void lidarDistance(DeviceImage<const std::uint8_t> support, DeviceImage<std::uint8_t> vertical,
                   DeviceImage<std::uint8_t> distance, cudaStream_t stream) {
  verticalDistanceKernel<<<static_cast<unsigned>((support.width + 127) / 128), 128, 0, stream>>>(support, vertical);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("verticalDistanceKernel");
  lidarDistanceKernel<<<pixelGrid(support.width, support.height), pixelBlock(), 0, stream>>>(
      DeviceImage<const std::uint8_t>{vertical.data, vertical.width, vertical.height, vertical.stride}, distance);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("lidarDistanceKernel");
}

void textureAndSaturation(DeviceImage<const std::uint8_t> image, DeviceImage<std::uint8_t> texture,
                          DeviceImage<std::uint8_t> saturated, cudaStream_t stream) {
  textureKernel<std::uint8_t><<<pixelGrid(image.width, image.height), pixelBlock(), 0, stream>>>(image, 0, 250, texture,
                                                                                                 saturated);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("textureKernel");
}

void textureAndSaturation(DeviceImage<const std::uint16_t> image, DeviceImage<std::uint8_t> texture,
                          DeviceImage<std::uint8_t> saturated, cudaStream_t stream) {
  // 16-bit images in 8-bit units (core/confidence.hpp).
  textureKernel<std::uint16_t><<<pixelGrid(image.width, image.height), pixelBlock(), 0, stream>>>(
      image, 8, 250 << 8, texture, saturated);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("textureKernel");
}

void disparityRange(DeviceImage<const std::int16_t> disparity, DeviceImage<std::uint8_t> range, cudaStream_t stream) {
  disparityRangeKernel<<<pixelGrid(disparity.width, disparity.height), pixelBlock(), 0, stream>>>(disparity, range);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("disparityRangeKernel");
}

void combineConfidence(const ConfidenceImages& inputs, const ConfidenceModel& model, bool lidarOnly, int paths,
                       const std::uint8_t* sigmoidTable, DeviceImage<const std::int16_t> disparity,
                       DeviceImage<std::uint8_t> confidence, cudaStream_t stream) {
  combineKernel<<<pixelGrid(disparity.width, disparity.height), pixelBlock(), 0, stream>>>(
      inputs, model, lidarOnly, paths, sigmoidTable, disparity, confidence);
  LIDAR_SGM_CUDA_CHECK_LAUNCH("combineKernel");
}

}  // namespace cuda
}  // namespace lidar_sgm
