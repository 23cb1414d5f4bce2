#pragma once
// The reference backend: the stages of stages.hpp run one after the other, single-threaded.

#include <cstdint>

#include "backends/common/cost_volume.hpp"
#include "backends/common/lidar_cost_table.hpp"
#include "backends/common/search_windows.hpp"
#include "core/backend.hpp"

namespace lidar_sgm {
namespace cpu_ref {
class StageClock;
}  // namespace cpu_ref

class CpuRefMatcher final : public MatcherBackend {
 public:
  Backend backend() const override { return Backend::CpuRef; }
  bool searchesGatedWindows() const override { return true; }
  void run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
           FrameResults& out) override;

 private:
  /// The camera cost: C_S with two cameras, C_S3 = (C_S + C_V + 1) >> 1 with the up camera.
  const MatchingCostVolume& cameraCost(const FramePlan& plan, const FrameInputs& in, cpu_ref::StageClock& clock,
                                       StageTimings& timings);
  void lidarCost(const FramePlan& plan, const LidarPoints& lidar, ImageView<std::uint8_t> support);
  const MatchingCostVolume& fuseCosts(const FramePlan& plan, const LidarPoints& lidar,
                                      const MatchingCostVolume& cameraCost, ImageView<const std::uint8_t> support);
  /// The matching cost of the plan's mode (C_S or C_S3, C_L, or Eq. 5's fusion of both).
  const MatchingCostVolume& matchingCost(const FramePlan& plan, const FrameInputs& in, cpu_ref::StageClock& clock,
                                         FrameResults& out);
  /// The confidence inputs that need S (core/confidence.hpp), read before the check invalidates.
  void confidenceInputs(const FramePlan& plan, ConfidenceInputs& out);
  void leftRightCheck(const FramePlan& plan, const LidarPoints* lidar);
  /// The right view's winners (rightIndex_), from the full or the windowed sum.
  void rightDisparityIndex(const FramePlan& plan);

  // Buffers kept between frames (resized only when the frame size changes).
  Image<std::uint64_t> leftCensus_;
  Image<std::uint64_t> rightCensus_;
  Image<std::uint64_t> upCensus_;      // Triple-SGM only
  MatchingCostVolume stereoCost_;      // C_S (left/right)
  MatchingCostVolume verticalCost_;    // C_V (left/up), Triple-SGM only
  MatchingCostVolume cameraCost_;      // C_S3 = (C_S + C_V + 1) >> 1, Triple-SGM only
  MatchingCostVolume lidarCost_;
  MatchingCostVolume fusedCost_;
  Image<std::uint16_t> lidarWeights_;  // w(p) of Eq. 5, fused mode
  AggregatedCostVolume sum_;
  SearchWindows windows_;                // the gated search's windows (Parameters::gatedSearch)
  WindowedMatchingCost windowedCost_;    // C on the windows
  WindowedAggregatedCost windowedSum_;   // S on the windows
  Image<std::int16_t> rawDisparity_;
  Image<std::int16_t> bestIndex_;
  Image<std::int16_t> rightIndex_;
  Image<std::uint8_t> coverage_;
  LidarCostTable table_;
  float tableSigma_ = 0;
  int tableCap_ = -1;
};

}  // namespace lidar_sgm
