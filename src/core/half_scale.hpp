#pragma once
// The paper's half-scale mode (Sec. IV-F): inputs scaled down 2x2, the disparity brought back up.
// Integer arithmetic only, in the core, so every backend sees the same half-scale inputs.

#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {

/// Size of the half-scale image of a `full`-pixel side: ceil(full / 2) (the last odd column/row
/// is averaged with itself).
inline int halfSize(int full) { return (full + 1) / 2; }

/// 2x2 box average, rounded half up: out(x, y) = (sum of in(2x..2x+1, 2y..2y+1) + 2) >> 2, with
/// the border pixel repeated past an odd edge. `out` is resized to halfSize() x halfSize().
/// `threads`: rows split among OpenMP threads (parallel_ranges.hpp; one without OpenMP), the same
/// result for any count, as for the functions below.
void downscaleHalf(ImageView<const std::uint8_t> in, Image<std::uint8_t>& out, int threads = 1);
void downscaleHalf(ImageView<const std::uint16_t> in, Image<std::uint16_t>& out, int threads = 1);
/// A gray image of either depth halved into the buffer of its depth; empty in, empty out.
GrayImageView downscaleHalf(const GrayImageView& in, Image<std::uint8_t>& buffer8, Image<std::uint16_t>& buffer16,
                            int threads = 1);

/// Every point moves to pixel (x/2, y/2) with its disparity halved, rounded half up (x16), so at
/// least 1/16 px: a point stays in front of the camera.
LidarPoints halveLidarPoints(const LidarPoints& points);
/// The same into `half`, with `samples` as scratch: both keep their memory between frames.
void halveLidarPoints(const LidarPoints& points, std::vector<LidarSample>& samples, LidarPoints& half);

/// full(x, y) = 2 * half(x/2, y/2), kInvalidDisparity staying invalid.
void upscaleDisparity(ImageView<const std::int16_t> half, ImageView<std::int16_t> full, int threads = 1);
/// full(x, y) = half(x/2, y/2).
void upscaleMask(ImageView<const std::uint8_t> half, ImageView<std::uint8_t> full, int threads = 1);

}  // namespace lidar_sgm
