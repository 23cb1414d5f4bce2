#pragma once
// The reference backend: the stages of stages.hpp run one after the other, single-threaded.

#include <cstdint>

#include "backends/common/cost_volume.hpp"
#include "backends/common/lidar_cost_table.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

class CpuRefMatcher final : public Matcher {
 public:
  explicit CpuRefMatcher(const Parameters& params) : Matcher(params) {}
  Backend backend() const override { return Backend::CpuRef; }

 protected:
  void run(const Parameters& params, const GrayImageView& left, const GrayImageView& right,
           const LidarPoints* lidar, MatchMode mode, ImageView<std::int16_t> disparity) override;
  void runWithUpCamera(const Parameters& params, const GrayImageView& left, const GrayImageView& right,
                       const GrayImageView& up, int ratio16, const LidarPoints* lidar, MatchMode mode,
                       ImageView<std::int16_t> disparity) override;

 private:
  /// Both entry points: `up` null for two cameras (then ratio16 is unused).
  void runStages(const Parameters& params, const GrayImageView& left, const GrayImageView& right, const GrayImageView* up, int ratio16,
                 const LidarPoints* lidar, MatchMode mode, ImageView<std::int16_t> disparity);

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
  Image<std::int16_t> rawDisparity_;
  Image<std::int16_t> bestIndex_;
  Image<std::int16_t> rightIndex_;
  Image<std::uint8_t> coverage_;
  LidarCostTable table_;
  float tableSigma_ = 0;
  int tableCap_ = -1;
};

}  // namespace lidar_sgm
