#pragma once
// The reference backend: the stages of stages.hpp run one after the other, single-threaded.

#include <cstdint>

#include "lidar_sgm/core/cost_volume.hpp"
#include "lidar_sgm/core/lidar_cost_table.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

class CpuRefMatcher final : public Matcher {
 public:
  explicit CpuRefMatcher(const Parameters& params) : Matcher(params) {}
  Backend backend() const override { return Backend::CpuRef; }

 protected:
  void run(const GrayImageView& left, const GrayImageView& right, const LidarPoints* lidar,
           MatchMode mode, ImageView<std::int16_t> disparity) override;

 private:
  // Buffers kept between frames (resized only when the frame size changes).
  Image<std::uint64_t> leftCensus_;
  Image<std::uint64_t> rightCensus_;
  MatchingCostVolume stereoCost_;
  MatchingCostVolume lidarCost_;
  MatchingCostVolume fusedCost_;
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
