#pragma once
// The CUDA backend's stages with cpu_ref's signatures (backends/common/stages.hpp), in host memory:
// each uploads its inputs (keeping the host's row stride, so padded rows reach the kernels),
// runs the kernel of kernels.hpp and downloads the result. They exist so that the cross-backend
// test compares every GPU kernel with its cpu_ref twin on its own; the matcher keeps everything
// on the device. Each throws std::runtime_error (CUDA's message) when no device can run it.
//
// censusCost, verticalCensusCost, lidarCost and fuseCosts run the cost functions the path
// recursion calls (matching_cost.cuh); aggregatePaths runs the recursion on a stored volume and
// the sum of selection.cu.

#include <cstddef>
#include <cstdint>

#include "backends/common/search_windows.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cuda {

void censusTransform(ImageView<const std::uint8_t> image, CensusType type, ImageView<std::uint64_t> census);
void censusTransform(ImageView<const std::uint16_t> image, CensusType type, ImageView<std::uint64_t> census);
void censusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> rightCensus,
                CensusType type, int minDisparity, MatchingCostVolume& cost);
void verticalCensusCost(ImageView<const std::uint64_t> leftCensus, ImageView<const std::uint64_t> upCensus,
                        CensusType type, int ratio16, int minDisparity, MatchingCostVolume& cost);
void combineCameraCosts(const MatchingCostVolume& horizontal, const MatchingCostVolume& vertical,
                        MatchingCostVolume& combined);
void lidarCost(const LidarPoints& points, const LidarCostTable& table, int minDisparity, MatchingCostVolume& cost,
               ImageView<std::uint8_t> support);
void lidarCoverage(const LidarPoints& points, int rows, ImageView<std::uint8_t> coverage);
void lidarSearchWindows(const LidarPoints& points, int minDisparity, int numDisparities, int rows, int margin,
                        SearchWindows& windows);
void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo, ImageView<const std::uint8_t> support,
               ImageView<const std::uint16_t> weights, bool stereoCostWithoutLidar, MatchingCostVolume& fused);
void fuseCosts(const MatchingCostVolume& lidar, const MatchingCostVolume& stereo, ImageView<const std::uint8_t> support,
               int alphaWeight256, bool stereoCostWithoutLidar, MatchingCostVolume& fused);
void aggregatePaths(const MatchingCostVolume& cost, int P1, int P2, int paths, AggregatedCostVolume& sum);
void selectDisparity(const AggregatedCostVolume& sum, int minDisparity, int uniquenessRatio, bool subpixel,
                     SelectedDisparity out);
void rightDisparityIndex(const AggregatedCostVolume& sum, int minDisparity, ImageView<std::int16_t> rightIndex);
void leftRightCheck(SelectedDisparity disparity, ImageView<const std::int16_t> rightIndex,
                    ImageView<const std::uint8_t> support, int minDisparity, int disp12MaxDiff, bool keepNoCounterpart);
void medianFilter(ImageView<const std::int16_t> in, int size, ImageView<std::int16_t> out);
void peakRatioMargin(const AggregatedCostVolume& sum, ImageView<const std::int16_t> bestIndex,
                     ImageView<std::uint8_t> margin, ImageView<std::uint16_t> bestCost);
void leftRightDifference(ImageView<const std::int16_t> bestIndex, ImageView<const std::int16_t> rightIndex,
                         int minDisparity, ImageView<std::uint8_t> difference);

/// A non-blocking CUDA stream for tests of DeviceFrame::stream, without CUDA headers in the test.
class DeviceStream {
 public:
  DeviceStream();
  ~DeviceStream();
  DeviceStream(const DeviceStream&) = delete;
  DeviceStream& operator=(const DeviceStream&) = delete;
  void* handle() const { return stream_; }  ///< the cudaStream_t
  void synchronize() const;

 private:
  void* stream_ = nullptr;
};

/// Device memory for tests of Matcher::computeOnDevice, without CUDA headers in the test.
class DeviceMemory {
 public:
  explicit DeviceMemory(std::size_t bytes);
  ~DeviceMemory();
  DeviceMemory(const DeviceMemory&) = delete;
  DeviceMemory& operator=(const DeviceMemory&) = delete;
  void* data() const { return data_; }
  std::size_t size() const { return bytes_; }
  void upload(const void* host, std::size_t bytes);
  void download(void* host, std::size_t bytes) const;
  /// Queued on `stream`: every byte set to `value`.
  void fillAsync(int value, const DeviceStream& stream);
  /// Queued on `stream`: the first `bytes` of `source` copied here.
  void copyAsync(const DeviceMemory& source, std::size_t bytes, const DeviceStream& stream);

 private:
  void* data_ = nullptr;
  std::size_t bytes_ = 0;
};

}  // namespace cuda
}  // namespace lidar_sgm
