// The host-memory stage entry points of cuda_stages.hpp: upload, one kernel, download.
#include "backends/cuda/cuda_stages.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <cuda_runtime_api.h>

#include "backends/cuda/cuda_error.hpp"
#include "backends/cuda/device_buffer.hpp"
#include "backends/cuda/kernels.hpp"
#include "backends/cuda/transfers.hpp"

namespace lidar_sgm {
namespace cuda {
namespace {

/// An image on the device with the host view's size and row stride.
template <typename T>
struct DeviceCopy {
  DeviceBuffer<T> buffer;
  DeviceImage<T> image;
  DeviceImage<const T> view() const { return DeviceImage<const T>{image.data, image.width, image.height, image.stride}; }
};

template <typename T>
DeviceCopy<T> allocateLike(int width, int height, std::ptrdiff_t stride) {
  DeviceCopy<T> copy;
  copy.buffer.reserve(static_cast<std::size_t>(stride) * (height > 0 ? height : 1));
  copy.image = DeviceImage<T>{copy.buffer.data(), width, height, stride};
  return copy;
}

template <typename T>
DeviceCopy<std::remove_const_t<T>> toDevice(ImageView<T> host) {
  using U = std::remove_const_t<T>;
  DeviceCopy<U> copy = allocateLike<U>(host.width, host.height, host.stride);
  const std::size_t pitch = static_cast<std::size_t>(host.stride) * sizeof(U);
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy2D(copy.buffer.data(), pitch, host.data, pitch, static_cast<std::size_t>(host.width) * sizeof(U),
                                    static_cast<std::size_t>(host.height), cudaMemcpyHostToDevice));
  return copy;
}

template <typename T>
void toHost(const DeviceCopy<T>& device, ImageView<T> host) {
  downloadImage(device.view(), host, nullptr);
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(nullptr));
}

template <typename T>
struct DeviceVolumeCopy {
  DeviceBuffer<T> buffer;
  DeviceVolume<T> volume;
  DeviceVolume<const T> view() const {
    return DeviceVolume<const T>{volume.data, volume.width, volume.height, volume.numDisparities};
  }
};

template <typename T>
DeviceVolumeCopy<T> allocateVolume(int width, int height, int D, std::size_t copies = 1) {
  DeviceVolumeCopy<T> v;
  v.volume = DeviceVolume<T>{nullptr, width, height, D};
  v.buffer.reserve(v.volume.size() * copies + 1);
  v.volume.data = v.buffer.data();
  return v;
}

template <typename T>
DeviceVolumeCopy<T> toDevice(const CostVolume<T>& host) {
  DeviceVolumeCopy<T> v = allocateVolume<T>(host.width(), host.height(), host.numDisparities());
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy(v.buffer.data(), host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice));
  return v;
}

template <typename T>
void toHost(const DeviceVolumeCopy<T>& device, CostVolume<T>& host) {
  host.resize(device.volume.width, device.volume.height, device.volume.numDisparities);
  LIDAR_SGM_CUDA_CHECK(cudaDeviceSynchronize());
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy(host.data(), device.buffer.data(), host.size() * sizeof(T), cudaMemcpyDeviceToHost));
}

struct DeviceLidarCopy {
  DeviceBuffer<int> pointPixels;
  DeviceBuffer<int> pixelStart;
  DeviceBuffer<int> disparities16;
  DeviceLidar lidar;
};

DeviceLidarCopy toDevice(const LidarPoints& points) {
  DeviceLidarCopy copy;
  uploadLidar(points, copy.pointPixels, copy.pixelStart, copy.disparities16, nullptr);
  copy.lidar = DeviceLidar{copy.pixelStart.data(), copy.disparities16.data(), points.width(), points.height()};
  return copy;
}

CostSettings cameraSettings(ImageView<const std::uint64_t> leftCensus, CensusType type, int minDisparity, int D) {
  CostSettings s;
  s.width = leftCensus.width;
  s.height = leftCensus.height;
  s.numDisparities = D;
  s.minDisparity = minDisparity;
  s.useCamera = true;
  s.censusScale = type == CensusType::Census9x7 ? 1 : 2;
  return s;
}

}  // namespace

void censusTransform(ImageView<const std::uint8_t> image, CensusType type, ImageView<std::uint64_t> census) {
  const auto in = toDevice(image);
  auto out = allocateLike<std::uint64_t>(census.width, census.height, census.stride);
  censusTransform(in.view(), type, out.image, nullptr);
  toHost(out, census);
}

void censusTransform(ImageView<const std::uint16_t> image, CensusType type, ImageView<std::uint64_t> census) {
  const auto in = toDevice(image);
  auto out = allocateLike<std::uint64_t>(census.width, census.height, census.stride);
  censusTransform(in.view(), type, out.image, nullptr);
  toHost(out, census);
}

void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost) {
  const auto left = toDevice(leftCensus);
  const auto right = toDevice(rightCensus);
  CostSettings s = cameraSettings(leftCensus, type, minDisparity, cost.numDisparities());
  s.leftCensus = left.view();
  s.rightCensus = right.view();
  auto out = allocateVolume<std::uint8_t>(s.width, s.height, s.numDisparities);
  matchingCostVolume(s, CostPart::Census, out.volume, nullptr);
  toHost(out, cost);
}

void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost) {
  const auto left = toDevice(leftCensus);
  const auto up = toDevice(upCensus);
  CostSettings s = cameraSettings(leftCensus, type, minDisparity, cost.numDisparities());
  s.leftCensus = left.view();
  s.upCensus = up.view();
  s.ratio16 = ratio16;
  auto out = allocateVolume<std::uint8_t>(s.width, s.height, s.numDisparities);
  matchingCostVolume(s, CostPart::VerticalCensus, out.volume, nullptr);
  toHost(out, cost);
}

void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined) {
  const auto h = toDevice(horizontal);
  const auto v = toDevice(vertical);
  auto out = allocateVolume<std::uint8_t>(horizontal.width(), horizontal.height(), horizontal.numDisparities());
  combineCameraCosts(h.view(), v.view(), out.volume, nullptr);
  toHost(out, combined);
}

void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity, MatchingCostVolume& cost,
               ImageView<std::uint8_t> support) {
  const DeviceLidarCopy lidar = toDevice(points);
  DeviceBuffer<std::uint8_t> entries;
  uploadVector(table.entries(), entries, nullptr);
  CostSettings s;
  s.width = points.width();
  s.height = points.height();
  s.numDisparities = cost.numDisparities();
  s.minDisparity = minDisparity;
  s.useLidar = true;
  s.lidar = lidar.lidar;
  s.table = DeviceCostTable{entries.data(), static_cast<int>(table.entries().size()), table.cap()};
  auto out = allocateVolume<std::uint8_t>(s.width, s.height, s.numDisparities);
  matchingCostVolume(s, CostPart::Lidar, out.volume, nullptr);
  toHost(out, cost);
  if (!support.empty()) {
    auto supportOut = allocateLike<std::uint8_t>(support.width, support.height, support.stride);
    lidarSupport(lidar.lidar, supportOut.image, nullptr);
    toHost(supportOut, support);
  }
}

void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage) {
  const DeviceLidarCopy lidar = toDevice(points);
  auto out = allocateLike<std::uint8_t>(coverage.width, coverage.height, coverage.stride);
  cuda::lidarCoverage(lidar.lidar, rows, out.image, nullptr);
  toHost(out, coverage);
}

void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows) {
  const DeviceLidarCopy lidar = toDevice(points);
  const int W = points.width();
  const int H = points.height();
  auto lowest = allocateLike<std::int16_t>(W, H, W);
  auto highest = allocateLike<std::int16_t>(W, H, W);
  auto first = allocateLike<std::int16_t>(W, H, W);
  auto count = allocateLike<std::int16_t>(W, H, W);
  cuda::lidarSearchWindows(lidar.lidar, minDisparity, numDisparities, rows, margin, lowest.image, highest.image,
                           first.image, count.image, nullptr);
  Image<std::int16_t> firsts(W, H);
  Image<std::int16_t> counts(W, H);
  toHost(first, firsts.view());
  toHost(count, counts.view());
  windows.resize(W, H, numDisparities);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) windows.set(x, y, firsts(x, y), counts(x, y));
  }
}

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo, ImageView<const std::uint8_t> support,
               ImageView<const std::uint16_t> weights, bool stereoCostWithoutLidar, MatchingCostVolume& fused) {
  const auto l = toDevice(lidar);
  const auto st = toDevice(stereo);
  const auto sup = toDevice(support);
  const auto w = toDevice(weights);
  auto out = allocateVolume<std::uint8_t>(stereo.width(), stereo.height(), stereo.numDisparities());
  fuseCosts(l.view(), st.view(), sup.view(), w.view(), 0, stereoCostWithoutLidar, out.volume, nullptr);
  toHost(out, fused);
}

void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo, ImageView<const std::uint8_t> support,
               int alphaWeight256, bool stereoCostWithoutLidar, MatchingCostVolume& fused) {
  const auto l = toDevice(lidar);
  const auto st = toDevice(stereo);
  const auto sup = toDevice(support);
  auto out = allocateVolume<std::uint8_t>(stereo.width(), stereo.height(), stereo.numDisparities());
  fuseCosts(l.view(), st.view(), sup.view(), DeviceImage<const std::uint16_t>{}, alphaWeight256, stereoCostWithoutLidar,
            out.volume, nullptr);
  toHost(out, fused);
}

namespace {

// The stage through L_r volumes of PathT, then S.
template <typename PathT>
void aggregateThrough(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum) {
  const auto c = toDevice(cost);
  auto pathCosts = allocateVolume<PathT>(cost.width(), cost.height(), cost.numDisparities(),
                                         static_cast<std::size_t>(paths));
  aggregatePaths(c.view(), DeviceWindows{}, P1, P2, paths, pathCosts.volume, nullptr);
  auto out = allocateVolume<std::uint16_t>(cost.width(), cost.height(), cost.numDisparities());
  selectDisparity(pathCosts.view(), paths, out.volume, 0, 0, false, DeviceImage<std::int16_t>{},
                  DeviceImage<std::int16_t>{}, nullptr);
  toHost(out, sum);
}

}  // namespace

void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum) {
  // The volume does not say which costs it holds: its largest value bounds them.
  if (pathCostsFit8Bits(largestMatchingCost(cost), P2)) {
    aggregateThrough<std::uint8_t>(cost, P1, P2, paths, sum);
  } else {
    aggregateThrough<std::uint16_t>(cost, P1, P2, paths, sum);
  }
}

void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out) {
  const auto s = toDevice(sum);
  auto disparity = allocateLike<std::int16_t>(out.disparity16.width, out.disparity16.height, out.disparity16.stride);
  auto best = allocateLike<std::int16_t>(out.bestIndex.width, out.bestIndex.height, out.bestIndex.stride);
  selectDisparity(s.view(), 1, DeviceVolume<std::uint16_t>{}, minDisparity, uniquenessRatio, subpixel,
                  disparity.image, best.image, nullptr);
  toHost(disparity, out.disparity16);
  toHost(best, out.bestIndex);
}

void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity, ImageView<std::int16_t> rightIndex) {
  const auto s = toDevice(sum);
  auto out = allocateLike<std::int16_t>(rightIndex.width, rightIndex.height, rightIndex.stride);
  cuda::rightDisparityIndex(s.view(), minDisparity, out.image, nullptr);
  toHost(out, rightIndex);
}

void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff, bool keepNoCounterpart) {
  auto d = toDevice(disparity.disparity16);
  auto best = toDevice(disparity.bestIndex);
  const auto right = toDevice(rightIndex);
  DeviceCopy<std::uint8_t> sup;
  if (!support.empty()) sup = toDevice(support);
  cuda::leftRightCheck(d.image, best.image, right.view(), support.empty() ? DeviceImage<const std::uint8_t>{} : sup.view(),
                       minDisparity, disp12MaxDiff, keepNoCounterpart, nullptr);
  toHost(d, disparity.disparity16);
  toHost(best, disparity.bestIndex);
}

void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out) {
  if (size > 5) throw std::invalid_argument("cuda medianFilter: size " + std::to_string(size) + " above 5");
  const auto i = toDevice(in);
  auto o = allocateLike<std::int16_t>(out.width, out.height, out.stride);
  cuda::medianFilter(i.view(), size, o.image, nullptr);
  toHost(o, out);
}

void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost) {
  const auto s = toDevice(sum);
  const auto best = toDevice(bestIndex);
  auto m = allocateLike<std::uint8_t>(margin.width, margin.height, margin.stride);
  auto c = allocateLike<std::uint16_t>(bestCost.width, bestCost.height, bestCost.stride);
  cuda::peakRatioMargin(s.view(), best.view(), m.image, c.image, nullptr);
  toHost(m, margin);
  toHost(c, bestCost);
}

void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference) {
  const auto best = toDevice(bestIndex);
  const auto right = toDevice(rightIndex);
  auto out = allocateLike<std::uint8_t>(difference.width, difference.height, difference.stride);
  cuda::leftRightDifference(best.view(), right.view(), minDisparity, out.image, nullptr);
  toHost(out, difference);
}

DeviceStream::DeviceStream() {
  cudaStream_t stream = nullptr;
  LIDAR_SGM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  stream_ = stream;
}
DeviceStream::~DeviceStream() { cudaStreamDestroy(static_cast<cudaStream_t>(stream_)); }
void DeviceStream::synchronize() const {
  LIDAR_SGM_CUDA_CHECK(cudaStreamSynchronize(static_cast<cudaStream_t>(stream_)));
}

DeviceMemory::DeviceMemory(std::size_t bytes) : bytes_(bytes) { LIDAR_SGM_CUDA_CHECK(cudaMalloc(&data_, bytes)); }
DeviceMemory::~DeviceMemory() { cudaFree(data_); }
void DeviceMemory::upload(const void* host, std::size_t bytes) {
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy(data_, host, bytes, cudaMemcpyHostToDevice));
}
void DeviceMemory::download(void* host, std::size_t bytes) const {
  LIDAR_SGM_CUDA_CHECK(cudaMemcpy(host, data_, bytes, cudaMemcpyDeviceToHost));
}
void DeviceMemory::fillAsync(int value, const DeviceStream& stream) {
  LIDAR_SGM_CUDA_CHECK(cudaMemsetAsync(data_, value, bytes_, static_cast<cudaStream_t>(stream.handle())));
}
void DeviceMemory::copyAsync(const DeviceMemory& source, std::size_t bytes, const DeviceStream& stream) {
  LIDAR_SGM_CUDA_CHECK(cudaMemcpyAsync(data_, source.data(), bytes, cudaMemcpyDeviceToDevice,
                                       static_cast<cudaStream_t>(stream.handle())));
}

}  // namespace cuda
}  // namespace lidar_sgm
