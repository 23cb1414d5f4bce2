#include "backends/cuda/cuda_matcher.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <cuda_runtime_api.h>

#include "backends/common/lidar_cost_table.hpp"
#include "backends/common/lidar_weights.hpp"
#include "backends/common/stages.hpp"
#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/device_buffer.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/transfers.hpp"
#include "lidar_sgm/core/confidence.hpp"

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

namespace {

// The points in time between which the stages of a frame ran, recorded on the stream.
enum Mark {
  kStart,
  kUploaded,
  kCensus,
  kLidar,
  kAggregated,
  kSelected,
  kChecked,
  kFiltered,
  kConfidence,
  kDownloaded,
  kMarks
};

}  // namespace

struct CudaMatcher::Device {
  cudaStream_t stream = nullptr;
  std::array<cudaEvent_t, kMarks> events{};

  DeviceBuffer<std::uint8_t> images8[3];    // left, right, up (8-bit frames)
  DeviceBuffer<std::uint16_t> images16[3];  // ... (16-bit frames)
  DeviceBuffer<std::uint64_t> census[3];
  DeviceBuffer<int> pixelStart;
  DeviceBuffer<int> disparities16;
  DeviceBuffer<std::uint8_t> table;
  DeviceBuffer<std::uint16_t> weights;  // adaptive alpha only
  DeviceBuffer<std::uint8_t> support;
  DeviceBuffer<std::uint8_t> coverage;
  DeviceBuffer<std::uint16_t> pathCosts;  // one L_r volume per path
  DeviceBuffer<std::uint16_t> sum;
  DeviceBuffer<std::int16_t> rawDisparity;
  DeviceBuffer<std::int16_t> bestIndex;
  DeviceBuffer<std::int16_t> rightIndex;
  DeviceBuffer<std::int16_t> disparity;
  DeviceBuffer<std::uint8_t> margin;
  DeviceBuffer<std::uint16_t> bestCost;
  DeviceBuffer<std::uint8_t> leftRightDifference;
  // The confidence's core part (confidence.cu) and its logistic table.
  DeviceBuffer<std::uint8_t> verticalDistance;
  DeviceBuffer<std::uint8_t> lidarDistance;
  DeviceBuffer<std::uint8_t> texture;
  DeviceBuffer<std::uint8_t> saturated;
  DeviceBuffer<std::uint8_t> disparityRange;
  DeviceBuffer<std::uint8_t> confidence;
  DeviceBuffer<std::uint8_t> sigmoid;
  LidarCostTable hostTable;
  float tableSigma = 0;
  int tableCap = -1;
  Image<std::uint16_t> hostWeights;

  Device() {
    LIDAR_SGM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
    for (cudaEvent_t& e : events) LIDAR_SGM_CUDA_CHECK(cudaEventCreate(&e));
    // The core's logistic curve, entry i at logit (i - 1024) / 64 (confidenceFromLogit256).
    std::vector<std::uint8_t> curve(2048);
    for (int i = 0; i < 2048; ++i) curve[static_cast<std::size_t>(i)] = confidenceFromLogit256(4 * (i - 1024));
    uploadVector(curve, sigmoid, stream);
    LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(stream));
  }
  ~Device() {
    for (cudaEvent_t e : events) {
      if (e != nullptr) cudaEventDestroy(e);
    }
    if (stream != nullptr) cudaStreamDestroy(stream);
  }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  void mark(Mark m) { LIDAR_SGM_CUDA_CHECK(cudaEventRecord(events[m], stream)); }
  double ms(Mark from, Mark to) const {
    float value = 0;
    LIDAR_SGM_CUDA_CHECK(cudaEventElapsedTime(&value, events[from], events[to]));
    return value;
  }
};

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

namespace {

template <typename T>
DeviceImage<T> denseImage(DeviceBuffer<std::remove_const_t<T>>& buffer, int width, int height) {
  buffer.reserve(static_cast<std::size_t>(width) * height);
  return DeviceImage<T>{buffer.data(), width, height, width};
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

void CudaMatcher::runStages(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                            FrameResults& out, bool inputsOnDevice, bool outputOnDevice) {
  Device& dev = *device_;
  const Parameters& p = plan.params;
  const MatchMode mode = plan.mode;
  const int width = plan.width;
  const int height = plan.height;
  const int D = plan.D;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  cudaStream_t stream = dev.stream;
  dev.mark(kStart);

  // Uploads: the images, the LiDAR points as LidarPoints keeps them, the cost table and weights.
  CostSettings s;
  s.width = width;
  s.height = height;
  s.numDisparities = D;
  s.minDisparity = plan.minDisparity;
  s.useCamera = plan.useCameras();
  s.useLidar = plan.useLidar;
  s.censusScale = plan.censusScale;
  s.ratio16 = plan.ratio16;
  const GrayImageView* cameras[3] = {&in.left, &in.right, &in.up};
  const int cameraCount = plan.cameras;
  const bool sixteen = s.useCamera && in.left.gray8.empty();
  // The cameras as the census reads them: the caller's device memory as it is, or an upload.
  DeviceImage<const std::uint8_t> images8[3];
  DeviceImage<const std::uint16_t> images16[3];
  for (int i = 0; i < cameraCount; ++i) {
    if (inputsOnDevice) {
      images8[i] = DeviceImage<const std::uint8_t>{cameras[i]->gray8.data, width, height, cameras[i]->gray8.stride};
      images16[i] = DeviceImage<const std::uint16_t>{cameras[i]->gray16.data, width, height, cameras[i]->gray16.stride};
    } else if (sixteen) {
      uploadImage(cameras[i]->gray16, dev.images16[i], stream);
      images16[i] = DeviceImage<const std::uint16_t>{dev.images16[i].data(), width, height, width};
    } else {
      uploadImage(cameras[i]->gray8, dev.images8[i], stream);
      images8[i] = DeviceImage<const std::uint8_t>{dev.images8[i].data(), width, height, width};
    }
  }
  if (s.useLidar) {
    uploadLidar(*in.lidar, dev.pixelStart, dev.disparities16, stream);
    s.lidar = DeviceLidar{dev.pixelStart.data(), dev.disparities16.data(), width, height};
    if (dev.tableSigma != p.sigma || dev.tableCap != p.lidarCostCap) {
      dev.hostTable = LidarCostTable(p.sigma, p.lidarCostCap);
      dev.tableSigma = p.sigma;
      dev.tableCap = p.lidarCostCap;
      uploadVector(dev.hostTable.entries(), dev.table, stream);
    }
    s.table = DeviceCostTable{dev.table.data(), static_cast<int>(dev.hostTable.entries().size()), dev.hostTable.cap()};
    if (mode == MatchMode::Fused) {
      if (!plan.adaptiveAlpha) {
        s.alphaWeight = plan.alphaWeight;
      } else {
        // The per-pixel LiDAR weight of Eq. 5, computed by the code every backend shares.
        dev.hostWeights.resize(width, height);
        lidarWeights(*in.lidar, p, dev.hostWeights.view());
        uploadImage(std::as_const(dev.hostWeights).view(), dev.weights, stream);
        s.weights = DeviceImage<const std::uint16_t>{dev.weights.data(), width, height, width};
      }
    }
    s.stereoCostWithoutLidar = p.stereoCostWithoutLidar;
  }
  dev.mark(kUploaded);

  if (s.useCamera) {
    DeviceImage<std::uint64_t> census[3];
    for (int i = 0; i < cameraCount; ++i) {
      census[i] = denseImage<std::uint64_t>(dev.census[i], width, height);
      if (sixteen) {
        cuda::censusTransform(images16[i], p.censusType, census[i], stream);
      } else {
        cuda::censusTransform(images8[i], p.censusType, census[i], stream);
      }
    }
    s.leftCensus = asConst(census[0]);
    s.rightCensus = asConst(census[1]);
    if (cameraCount == 3) s.upCensus = asConst(census[2]);
  }
  dev.mark(kCensus);
  const DeviceImage<std::uint8_t> support = denseImage<std::uint8_t>(dev.support, width, height);
  if (s.useLidar) cuda::lidarSupport(s.lidar, support, stream);
  dev.mark(kLidar);

  // Eq. 1 with the matching cost (C_S, C_S3, C_L or Eq. 5) computed inside the recursion.
  dev.pathCosts.reserve(pixels * D * static_cast<std::size_t>(p.paths));
  const DeviceVolume<std::uint16_t> pathCosts{dev.pathCosts.data(), width, height, D};
  cuda::aggregatePaths(s, p.P1, p.P2, p.paths, pathCosts, stream);
  dev.mark(kAggregated);

  dev.sum.reserve(pixels * D);
  const DeviceVolume<std::uint16_t> sum{dev.sum.data(), width, height, D};
  const DeviceImage<std::int16_t> raw = denseImage<std::int16_t>(dev.rawDisparity, width, height);
  const DeviceImage<std::int16_t> best = denseImage<std::int16_t>(dev.bestIndex, width, height);
  cuda::selectDisparity(asConst(pathCosts), p.paths, sum, plan.minDisparity, p.uniquenessRatio, p.subpixel, raw, best,
                        stream);
  // The confidence inputs that need S (core/confidence.hpp), read before the check invalidates.
  const bool confidenceLr = plan.confidenceLr;
  const DeviceImage<std::uint8_t> margin = denseImage<std::uint8_t>(dev.margin, width, height);
  const DeviceImage<std::uint16_t> bestCost = denseImage<std::uint16_t>(dev.bestCost, width, height);
  if (plan.confidence) cuda::peakRatioMargin(asConst(sum), asConst(best), margin, bestCost, stream);
  dev.mark(kSelected);

  const bool lrCheck = plan.lrCheck;
  const DeviceImage<std::int16_t> rightIndex = denseImage<std::int16_t>(dev.rightIndex, width, height);
  const DeviceImage<std::uint8_t> difference = denseImage<std::uint8_t>(dev.leftRightDifference, width, height);
  if (confidenceLr || lrCheck) cuda::rightDisparityIndex(asConst(sum), p.minDisparity, rightIndex, stream);
  if (confidenceLr) cuda::leftRightDifference(asConst(best), asConst(rightIndex), p.minDisparity, difference, stream);
  if (lrCheck) {
    DeviceImage<const std::uint8_t> checkSupport;
    if (plan.lrCheckTrustsLidar) {
      const DeviceImage<std::uint8_t> coverage = denseImage<std::uint8_t>(dev.coverage, width, height);
      cuda::lidarCoverage(s.lidar, p.lidarCoverageRows, coverage, stream);
      checkSupport = asConst(coverage);
    }
    cuda::leftRightCheck(raw, best, asConst(rightIndex), checkSupport, p.minDisparity, p.disp12MaxDiff,
                         /*keepNoCounterpart=*/plan.lrCheckTrustsLidar, stream);
  }
  dev.mark(kChecked);
  // The result straight into the caller's device memory, or into ours to be downloaded.
  const DeviceImage<std::int16_t> filtered =
      outputOnDevice ? DeviceImage<std::int16_t>{disparity.data, width, height, disparity.stride}
                     : denseImage<std::int16_t>(dev.disparity, width, height);
  cuda::medianFilter(asConst(raw), p.medianSize, filtered, stream);
  dev.mark(kFiltered);

  // The confidence's core part, as the core computes it on the host (core/confidence_inputs.hpp).
  const DeviceImage<std::uint8_t> distance = denseImage<std::uint8_t>(dev.lidarDistance, width, height);
  const DeviceImage<std::uint8_t> texture = denseImage<std::uint8_t>(dev.texture, width, height);
  const DeviceImage<std::uint8_t> saturated = denseImage<std::uint8_t>(dev.saturated, width, height);
  const DeviceImage<std::uint8_t> range = denseImage<std::uint8_t>(dev.disparityRange, width, height);
  const DeviceImage<std::uint8_t> confidence = denseImage<std::uint8_t>(dev.confidence, width, height);
  if (plan.confidence) {
    if (!s.useLidar) LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(support.data, 0, pixels, stream));
    cuda::lidarDistance(asConst(support), denseImage<std::uint8_t>(dev.verticalDistance, width, height), distance,
                        stream);
    if (!s.useCamera) {
      // LiDAR-only: no image, so no texture; no right view, so no counterpart.
      LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(texture.data, 0, pixels, stream));
      LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(saturated.data, 0, pixels, stream));
      LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(difference.data, kNoCounterpartDifference, pixels, stream));
    } else if (sixteen) {
      cuda::textureAndSaturation(images16[0], texture, saturated, stream);
    } else {
      cuda::textureAndSaturation(images8[0], texture, saturated, stream);
    }
    cuda::disparityRange(asConst(filtered), range, stream);
    const ConfidenceImages inputs{asConst(margin),   asConst(bestCost),  asConst(difference), asConst(distance),
                                  asConst(texture),  asConst(saturated), asConst(range)};
    cuda::combineConfidence(inputs, confidenceModel(mode), mode == MatchMode::LidarOnly, p.paths, dev.sigmoid.data(),
                            asConst(filtered), confidence, stream);
  }
  dev.mark(kConfidence);

  // Downloads: the disparity, and what the core reads besides it.
  if (!outputOnDevice) downloadImage(asConst(filtered), disparity, stream);
  out.support.resize(width, height);
  if (s.useLidar) {
    downloadImage(asConst(support), out.support.view(), stream);
  } else {
    out.support.fill(0);
  }
  if (plan.confidence) {
    ConfidenceInputs& inputs = out.confidenceInputs;
    const auto download = [&](DeviceImage<std::uint8_t> from, Image<std::uint8_t>& to) {
      to.resize(width, height);
      downloadImage(asConst(from), to.view(), stream);
    };
    download(margin, inputs.margin);
    inputs.bestCost.resize(width, height);
    downloadImage(asConst(bestCost), inputs.bestCost.view(), stream);
    download(difference, inputs.leftRightDifference);
    download(distance, inputs.lidarDistance);
    download(texture, inputs.texture);
    download(saturated, inputs.saturated);
    download(range, inputs.disparityRange);
    download(confidence, out.confidence);
  }
  dev.mark(kDownloaded);
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(stream));

  // Kernel time per stage (CUDA events). The costs are computed inside the aggregation, so
  // censusCost, lidarCost's volume and fuseCosts have no time of their own.
  out.timings.transfers = dev.ms(kStart, kUploaded) + dev.ms(kConfidence, kDownloaded);
  out.timings.census = dev.ms(kUploaded, kCensus);
  out.timings.lidarCost = dev.ms(kCensus, kLidar);
  out.timings.aggregatePaths = dev.ms(kLidar, kAggregated);
  out.timings.selectDisparity = dev.ms(kAggregated, kSelected);
  out.timings.leftRightCheck = dev.ms(kSelected, kChecked);
  out.timings.medianFilter = dev.ms(kChecked, kFiltered);
  out.timings.confidence = dev.ms(kFiltered, kConfidence);
}

namespace {

template <typename T>
ImageView<const T> downloaded(ImageView<const T> device, int width, int height, Image<T>& host) {
  host.resize(width, height);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2D(host.data(), static_cast<std::size_t>(width) * sizeof(T), device.data,
                                    static_cast<std::size_t>(device.stride) * sizeof(T),
                                    static_cast<std::size_t>(width) * sizeof(T), static_cast<std::size_t>(height),
                                    cudaMemcpyDeviceToHost));
  return std::as_const(host).view();
}

// A gray image in device memory, copied into the host buffer of its depth.
GrayImageView downloaded(const GrayImageView& device, Image<std::uint8_t>& host8, Image<std::uint16_t>& host16) {
  if (device.empty()) return {};
  if (!device.gray8.empty()) return downloaded(device.gray8, device.width(), device.height(), host8);
  return downloaded(device.gray16, device.width(), device.height(), host16);
}

}  // namespace

void CudaMatcher::copyToHost(const DeviceFrame& frame, bool images, DeviceFrameCopy& host) {
  if (frame.lidar != nullptr && frame.lidarCount > 0) {
    host.samples.resize(frame.lidarCount);
    LIDAR_SGM_CUDA_CHECK(cudaMemcpy(host.samples.data(), frame.lidar, frame.lidarCount * sizeof(LidarSample),
                                    cudaMemcpyDeviceToHost));
  }
  if (images) {
    host.left = downloaded(frame.left, host.left8, host.left16);
    host.right = downloaded(frame.right, host.right8, host.right16);
  }
}

void CudaMatcher::copyToDevice(ImageView<const std::int16_t> host, ImageView<std::int16_t> device) {
  const std::size_t rowBytes = static_cast<std::size_t>(host.width) * sizeof(std::int16_t);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2D(device.data, static_cast<std::size_t>(device.stride) * sizeof(std::int16_t),
                                    host.data, static_cast<std::size_t>(host.stride) * sizeof(std::int16_t), rowBytes,
                                    static_cast<std::size_t>(host.height), cudaMemcpyHostToDevice));
}

}  // namespace cuda
}  // namespace lidar_sgm
