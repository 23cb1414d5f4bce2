#include "backends/cuda/cuda_matcher.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include <cuda_runtime_api.h>

#include "backends/common/lidar_weights.hpp"
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/matcher_device.hpp"
#include "backends/cuda/transfers.hpp"

namespace lidar_sgm {

std::unique_ptr<MatcherBackend> createCudaMatcher() { return std::make_unique<cuda::CudaMatcher>(); }

std::string cudaBackendUnavailable() { return cuda::cudaUnavailableReason(); }

namespace cuda {

std::string cudaUnavailableReason() {
  int count = 0;
  const cudaError_t error = cudaGetDeviceCount(&count);
  if (error != cudaSuccess) {
    (void)cudaGetLastError();
    return std::string("no usable CUDA device (") + cudaGetErrorName(error) + ": " + cudaGetErrorString(error) + ")";
  }
  if (count == 0) return "no CUDA device";
  return "";
}

struct CudaMatcher::FrameImages {
  CostSettings costs;  // what the matching cost is computed from (cost_volume.cu)
  bool sixteen = false;
  // The cameras as the census reads them (left, right, up): the caller's device memory, or ours.
  DeviceImage<const std::uint8_t> images8[3];
  DeviceImage<const std::uint16_t> images16[3];
  DeviceImage<std::uint64_t> census[3];
  DeviceImage<std::uint8_t> support, coverage;
  DeviceWindows windows;  // empty: the whole range at every pixel
  DeviceVolume<std::uint8_t> matchingCost;
  bool paths8 = false;                      // the L_r volumes in 8 bits (pathCosts8), else pathCosts
  DeviceVolume<std::uint8_t> pathCosts8;
  DeviceVolume<std::uint16_t> pathCosts, sum;
  DeviceImage<std::int16_t> raw, best, rightIndex, filtered;
  DeviceImage<std::uint8_t> margin, difference;
  DeviceImage<std::uint16_t> bestCost;
  DeviceImage<std::uint8_t> verticalDistance, distance, texture, saturated, range, confidence;
};

namespace {

template <typename T>
DeviceImage<T> denseImage(DeviceBuffer<std::remove_const_t<T>>& buffer, int width, int height) {
  buffer.reserve(static_cast<std::size_t>(width) * height);
  return DeviceImage<T>{buffer.data(), width, height, width};
}

template <typename T>
DeviceVolume<T> denseVolume(DeviceBuffer<T>& buffer, int width, int height, int D, int copies = 1) {
  buffer.reserve(static_cast<std::size_t>(width) * height * D * static_cast<std::size_t>(copies));
  return DeviceVolume<T>{buffer.data(), width, height, D};
}

// A W x H image at `offset` bytes into the read-back allocation (readback.hpp).
template <typename T>
DeviceImage<T> readbackImage(DeviceBuffer<std::uint8_t>& readback, std::size_t offset, int width, int height) {
  return DeviceImage<T>{reinterpret_cast<T*>(readback.data() + offset), width, height, width};
}

// Rows of a dense W x H image in pinned memory into a host view (any stride).
template <typename T>
void unpack(const std::uint8_t* pinned, std::size_t offset, ImageView<T> to) {
  const T* from = reinterpret_cast<const T*>(pinned + offset);
  const std::size_t rowBytes = static_cast<std::size_t>(to.width) * sizeof(T);
  for (int y = 0; y < to.height; ++y) std::memcpy(to.row(y), from + static_cast<std::size_t>(y) * to.width, rowBytes);
}

template <typename T>
DeviceImage<const T> asConst(DeviceImage<T> image) {
  return DeviceImage<const T>{image.data, image.width, image.height, image.stride};
}

template <typename T>
DeviceVolume<const T> asConst(DeviceVolume<T> volume) {
  return DeviceVolume<const T>{volume.data, volume.width, volume.height, volume.numDisparities};
}

}  // namespace

CudaMatcher::CudaMatcher() {
  const std::string why = cudaUnavailableReason();
  if (!why.empty()) throw std::runtime_error("backend cuda: " + why);
  device_ = std::make_unique<Device>();
}

CudaMatcher::~CudaMatcher() = default;

void CudaMatcher::run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                      FrameResults& out) {
  runStages(plan, in, disparity, out, /*inputsOnDevice=*/false, /*outputOnDevice=*/false);
}

void CudaMatcher::runOnDevice(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                              MemorySpace disparitySpace, FrameResults& out) {
  runStages(plan, in, disparity, out, /*inputsOnDevice=*/true, disparitySpace == MemorySpace::Device);
}

void CudaMatcher::runStages(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                            FrameResults& out, bool inputsOnDevice, bool outputOnDevice) {
  Device& dev = *device_;
  dev.mark(kStart);
  FrameImages frame;
  reserveImages(plan, frame);
  // The result straight into the caller's device memory, or into ours to be downloaded.
  if (outputOnDevice) frame.filtered = DeviceImage<std::int16_t>{disparity.data, plan.width, plan.height, disparity.stride};
  uploadCameras(plan, in, inputsOnDevice, frame);
  if (plan.useLidar) uploadLidar(plan, *in.lidar, frame);
  dev.mark(kUploaded);
  if (plan.gatedSearch) searchWindows(plan, frame);
  censusTransforms(plan, frame);
  dev.mark(kCensus);
  if (plan.useLidar) cuda::lidarSupport(frame.costs.lidar, frame.support, dev.stream);
  dev.mark(kLidar);
  cuda::matchingCostVolume(frame.costs, CostPart::Matching, frame.matchingCost, dev.stream);
  dev.mark(kCosts);
  aggregatePaths(plan, frame);
  dev.mark(kAggregated);
  selectDisparity(plan, frame);
  dev.mark(kSelected);
  leftRightCheck(plan, frame);
  dev.mark(kChecked);
  cuda::medianFilter(asConst(frame.raw), plan.params.medianSize, frame.filtered, dev.stream);
  dev.mark(kFiltered);
  if (plan.confidence) confidence(plan, frame);
  dev.mark(kConfidence);
  downloadResults(plan, outputOnDevice);
  dev.mark(kDownloaded);
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(dev.stream));
  unpackResults(plan, disparity, outputOnDevice, out);
  recordTimings(plan, out.timings);
}

// The buffers every frame uses, whatever its plan (grown only).
void CudaMatcher::reserveImages(const FramePlan& plan, FrameImages& f) {
  Device& dev = *device_;
  const int W = plan.width;
  const int H = plan.height;
  const ReadbackLayout layout(W, H);
  dev.readback.reserve(layout.bytes);
  f.support = readbackImage<std::uint8_t>(dev.readback, layout.support, W, H);
  f.margin = readbackImage<std::uint8_t>(dev.readback, layout.margin, W, H);
  f.bestCost = readbackImage<std::uint16_t>(dev.readback, layout.bestCost, W, H);
  f.difference = readbackImage<std::uint8_t>(dev.readback, layout.difference, W, H);
  f.distance = readbackImage<std::uint8_t>(dev.readback, layout.distance, W, H);
  f.texture = readbackImage<std::uint8_t>(dev.readback, layout.texture, W, H);
  f.saturated = readbackImage<std::uint8_t>(dev.readback, layout.saturated, W, H);
  f.range = readbackImage<std::uint8_t>(dev.readback, layout.range, W, H);
  f.confidence = readbackImage<std::uint8_t>(dev.readback, layout.confidence, W, H);
  f.filtered = readbackImage<std::int16_t>(dev.readback, layout.disparity, W, H);
  f.matchingCost = denseVolume(dev.matchingCost, W, H, plan.D);
  f.paths8 = pathCostsFit8Bits(largestMatchingCost(plan), plan.params.P2);
  if (f.paths8) {
    f.pathCosts8 = denseVolume(dev.pathCosts8, W, H, plan.D, plan.params.paths);
  } else {
    f.pathCosts = denseVolume(dev.pathCosts, W, H, plan.D, plan.params.paths);
  }
  f.sum = denseVolume(dev.sum, W, H, plan.D);
  f.raw = denseImage<std::int16_t>(dev.rawDisparity, W, H);
  f.best = denseImage<std::int16_t>(dev.bestIndex, W, H);
  f.rightIndex = denseImage<std::int16_t>(dev.rightIndex, W, H);
  f.verticalDistance = denseImage<std::uint8_t>(dev.verticalDistance, W, H);
}

void CudaMatcher::uploadCameras(const FramePlan& plan, const FrameInputs& in, bool inputsOnDevice, FrameImages& f) {
  Device& dev = *device_;
  const int W = plan.width;
  const int H = plan.height;
  const GrayImageView* cameras[3] = {&in.left, &in.right, &in.up};
  f.sixteen = plan.useCameras() && in.left.gray8.empty();
  for (int i = 0; i < plan.cameras; ++i) {
    const GrayImageView& camera = *cameras[i];
    if (inputsOnDevice) {
      f.images8[i] = DeviceImage<const std::uint8_t>{camera.gray8.data, W, H, camera.gray8.stride};
      f.images16[i] = DeviceImage<const std::uint16_t>{camera.gray16.data, W, H, camera.gray16.stride};
    } else if (f.sixteen) {
      uploadImage(camera.gray16, dev.images16[i], dev.stream);
      f.images16[i] = DeviceImage<const std::uint16_t>{dev.images16[i].data(), W, H, W};
    } else {
      uploadImage(camera.gray8, dev.images8[i], dev.stream);
      f.images8[i] = DeviceImage<const std::uint8_t>{dev.images8[i].data(), W, H, W};
    }
  }
  CostSettings& s = f.costs;
  s.width = W;
  s.height = H;
  s.numDisparities = plan.D;
  s.minDisparity = plan.minDisparity;
  s.useCamera = plan.useCameras();
  s.useLidar = plan.useLidar;
  s.censusScale = plan.censusScale;
  s.ratio16 = plan.ratio16;
}

// The LiDAR points as LidarPoints keeps them, the cost table and, with an adaptive alpha, the
// per-pixel weights of Eq. 5 (computed on the host by the code every backend shares).
void CudaMatcher::uploadLidar(const FramePlan& plan, const LidarPoints& lidar, FrameImages& f) {
  Device& dev = *device_;
  const Parameters& p = plan.params;
  CostSettings& s = f.costs;
  cuda::uploadLidar(lidar, dev.pointPixels, dev.pixelStart, dev.disparities16, dev.stream);
  s.lidar = DeviceLidar{dev.pixelStart.data(), dev.disparities16.data(), plan.width, plan.height};
  if (dev.tableSigma != p.sigma || dev.tableCap != p.lidarCostCap) {
    dev.hostTable = LidarCostTable(p.sigma, p.lidarCostCap);
    dev.tableSigma = p.sigma;
    dev.tableCap = p.lidarCostCap;
    uploadVector(dev.hostTable.entries(), dev.table, dev.stream);
  }
  s.table = DeviceCostTable{dev.table.data(), static_cast<int>(dev.hostTable.entries().size()), dev.hostTable.cap()};
  if (plan.mode == MatchMode::Fused && !plan.adaptiveAlpha) s.alphaWeight = plan.alphaWeight;
  if (plan.adaptiveAlpha) {
    dev.hostWeights.resize(plan.width, plan.height);
    lidarWeights(lidar, p, dev.hostWeights.view());
    uploadImage(std::as_const(dev.hostWeights).view(), dev.weights, dev.stream);
    s.weights = DeviceImage<const std::uint16_t>{dev.weights.data(), plan.width, plan.height, plan.width};
  }
  s.stereoCostWithoutLidar = p.stereoCostWithoutLidar;
}

// The gate's windows from the points on the device (uploadLidar ran before): nothing computed on
// the host or uploaded.
void CudaMatcher::searchWindows(const FramePlan& plan, FrameImages& f) {
  Device& dev = *device_;
  const Parameters& p = plan.params;
  const int W = plan.width;
  const int H = plan.height;
  const auto first = denseImage<std::int16_t>(dev.windowFirst, W, H);
  const auto count = denseImage<std::int16_t>(dev.windowCount, W, H);
  cuda::lidarSearchWindows(f.costs.lidar, plan.minDisparity, plan.D, p.gatedSearchRows, p.gatedSearchMargin,
                           denseImage<std::int16_t>(dev.windowLowest, W, H),
                           denseImage<std::int16_t>(dev.windowHighest, W, H), first, count, dev.stream);
  f.windows = DeviceWindows{first.data, count.data};
}

void CudaMatcher::censusTransforms(const FramePlan& plan, FrameImages& f) {
  Device& dev = *device_;
  for (int i = 0; i < plan.cameras; ++i) {
    f.census[i] = denseImage<std::uint64_t>(dev.census[i], plan.width, plan.height);
    if (f.sixteen) {
      cuda::censusTransform(f.images16[i], plan.params.censusType, f.census[i], dev.stream);
    } else {
      cuda::censusTransform(f.images8[i], plan.params.censusType, f.census[i], dev.stream);
    }
  }
  if (!plan.useCameras()) return;
  f.costs.leftCensus = asConst(f.census[0]);
  f.costs.rightCensus = asConst(f.census[1]);
  if (plan.upCamera()) f.costs.upCensus = asConst(f.census[2]);
}

// Eq. 1 on the matching cost (C_S, C_S3, C_L or Eq. 5) stored before.
void CudaMatcher::aggregatePaths(const FramePlan& plan, FrameImages& f) {
  const Parameters& p = plan.params;
  if (f.paths8) {
    cuda::aggregatePaths(asConst(f.matchingCost), f.windows, p.P1, p.P2, p.paths, f.pathCosts8, device_->stream);
  } else {
    cuda::aggregatePaths(asConst(f.matchingCost), f.windows, p.P1, p.P2, p.paths, f.pathCosts, device_->stream);
  }
}

// S, the winners and the confidence inputs that need S, read before the check invalidates.
void CudaMatcher::selectDisparity(const FramePlan& plan, FrameImages& f) {
  const Parameters& p = plan.params;
  cudaStream_t stream = device_->stream;
  if (f.paths8) {
    cuda::selectDisparity(asConst(f.pathCosts8), p.paths, f.sum, plan.minDisparity, p.uniquenessRatio, p.subpixel,
                          f.raw, f.best, stream);
  } else {
    cuda::selectDisparity(asConst(f.pathCosts), p.paths, f.sum, plan.minDisparity, p.uniquenessRatio, p.subpixel,
                          f.raw, f.best, stream);
  }
  if (plan.confidence) cuda::peakRatioMargin(asConst(f.sum), asConst(f.best), f.margin, f.bestCost, stream);
}

// The right view's winners, read diagonally from S, serve the confidence's left-right difference
// (before the check) and the check itself.
void CudaMatcher::leftRightCheck(const FramePlan& plan, FrameImages& f) {
  Device& dev = *device_;
  if (plan.confidenceLr || plan.lrCheck) {
    cuda::rightDisparityIndex(asConst(f.sum), plan.minDisparity, f.rightIndex, dev.stream);
  }
  if (plan.confidenceLr) {
    cuda::leftRightDifference(asConst(f.best), asConst(f.rightIndex), plan.minDisparity, f.difference, dev.stream);
  }
  if (!plan.lrCheck) return;
  DeviceImage<const std::uint8_t> covered;
  if (plan.lrCheckTrustsLidar) {
    f.coverage = denseImage<std::uint8_t>(dev.coverage, plan.width, plan.height);
    cuda::lidarCoverage(f.costs.lidar, plan.params.lidarCoverageRows, f.coverage, dev.stream);
    covered = asConst(f.coverage);
  }
  cuda::leftRightCheck(f.raw, f.best, asConst(f.rightIndex), covered, plan.minDisparity, plan.params.disp12MaxDiff,
                       /*keepNoCounterpart=*/plan.lrCheckTrustsLidar, dev.stream);
}

// The confidence's core part, as the core computes it on the host (core/confidence_inputs.hpp).
void CudaMatcher::confidence(const FramePlan& plan, FrameImages& f) {
  Device& dev = *device_;
  cudaStream_t stream = dev.stream;
  const std::size_t pixels = static_cast<std::size_t>(plan.width) * plan.height;
  if (!plan.useLidar) LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(f.support.data, 0, pixels, stream));
  cuda::lidarDistance(asConst(f.support), f.verticalDistance, f.distance, stream);
  if (!plan.useCameras()) {
    // LiDAR-only: no image, so no texture; no right view, so no counterpart.
    LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(f.texture.data, 0, pixels, stream));
    LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(f.saturated.data, 0, pixels, stream));
    LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(f.difference.data, kNoCounterpartDifference, pixels, stream));
  } else if (f.sixteen) {
    cuda::textureAndSaturation(f.images16[0], f.texture, f.saturated, stream);
  } else {
    cuda::textureAndSaturation(f.images8[0], f.texture, f.saturated, stream);
  }
  cuda::disparityRange(asConst(f.filtered), f.range, stream);
  const ConfidenceImages inputs{asConst(f.margin),  asConst(f.bestCost),  asConst(f.difference), asConst(f.distance),
                                asConst(f.texture), asConst(f.saturated), asConst(f.range)};
  cuda::combineConfidence(inputs, confidenceModel(plan.mode), plan.mode == MatchMode::LidarOnly, plan.params.paths,
                          dev.sigmoid.data(), asConst(f.filtered), f.confidence, stream);
}

// The disparity, and what the core reads besides it: one copy of the read-back allocation into
// pinned memory (up to the disparity when it stays on the device).
void CudaMatcher::downloadResults(const FramePlan& plan, bool outputOnDevice) {
  Device& dev = *device_;
  const ReadbackLayout layout(plan.width, plan.height);
  const std::size_t bytes = outputOnDevice ? layout.disparity : layout.bytes;
  dev.pinned.reserve(bytes);
  LIDAR_SGM_CUDA_CHECK(
      cudaMemcpyAsync(dev.pinned.data(), dev.readback.data(), bytes, cudaMemcpyDeviceToHost, dev.stream));
}

// After the stream is done: the pinned copy into the caller's disparity and the core's images.
void CudaMatcher::unpackResults(const FramePlan& plan, ImageView<std::int16_t> disparity, bool outputOnDevice,
                                FrameResults& out) {
  const std::uint8_t* pinned = device_->pinned.data();
  const ReadbackLayout layout(plan.width, plan.height);
  const int W = plan.width;
  const int H = plan.height;
  if (!outputOnDevice) unpack(pinned, layout.disparity, disparity);
  out.support.resize(W, H);
  if (plan.useLidar) {
    unpack(pinned, layout.support, out.support.view());
  } else {
    out.support.fill(0);
  }
  if (!plan.confidence) return;
  ConfidenceInputs& in = out.confidenceInputs;
  const auto take = [&](std::size_t offset, auto& to) {
    to.resize(W, H);
    unpack(pinned, offset, to.view());
  };
  take(layout.margin, in.margin);
  take(layout.bestCost, in.bestCost);
  take(layout.difference, in.leftRightDifference);
  take(layout.distance, in.lidarDistance);
  take(layout.texture, in.texture);
  take(layout.saturated, in.saturated);
  take(layout.range, in.disparityRange);
  take(layout.confidence, out.confidence);
}

// Kernel time per stage (CUDA events). The stored matching cost is one kernel for every term: its
// time goes to the stage that names the frame's cost (censusCost, lidarCost or fuseCosts).
void CudaMatcher::recordTimings(const FramePlan& plan, StageTimings& timings) const {
  const Device& dev = *device_;
  timings.transfers = dev.ms(kStart, kUploaded) + dev.ms(kConfidence, kDownloaded);
  timings.census = dev.ms(kUploaded, kCensus);
  timings.lidarCost = dev.ms(kCensus, kLidar);
  const double costs = dev.ms(kLidar, kCosts);
  if (plan.mode == MatchMode::Fused) {
    timings.fuseCosts = costs;
  } else if (plan.mode == MatchMode::LidarOnly) {
    timings.lidarCost += costs;
  } else {
    timings.censusCost = costs;
  }
  timings.aggregatePaths = dev.ms(kCosts, kAggregated);
  timings.selectDisparity = dev.ms(kAggregated, kSelected);
  timings.leftRightCheck = dev.ms(kSelected, kChecked);
  timings.medianFilter = dev.ms(kChecked, kFiltered);
  timings.confidence = dev.ms(kFiltered, kConfidence);
}

}  // namespace cuda
}  // namespace lidar_sgm
