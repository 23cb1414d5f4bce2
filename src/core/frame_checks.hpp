#pragma once
// The checks every frame passes before it is planned: which inputs were given, whether their
// sizes and bit depths agree, and the mode and size that follow from them.

#include <cstdint>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

struct CheckedFrame {
  MatchMode mode = MatchMode::StereoOnly;
  int width = 0;
  int height = 0;
};

/// Matcher::compute's inputs; throws std::invalid_argument naming the problem.
CheckedFrame checkFrame(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                        const LidarPoints* lidar, ImageView<std::int16_t> disparity);

/// Matcher::computeOnDevice's inputs (the sizes only: device memory is not read here).
CheckedFrame checkDeviceFrame(const DeviceFrame& frame, ImageView<std::int16_t> disparity);

}  // namespace lidar_sgm
