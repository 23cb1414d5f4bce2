#pragma once
/// @file search_window_rule.hpp  The arithmetic of the LiDAR gate (lidar_search_windows.hpp), on
/// the host and in CUDA kernels alike: a point's x16 disparity in 16 bits, and a pixel's window
/// from the extremes of its neighbourhood's points.

#include <cstdint>

#include "backends/common/host_device.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {

/// The extremes of a neighbourhood without a point: above and below every clamped disparity.
constexpr std::int16_t kSearchNoLowest = 32767;
constexpr std::int16_t kSearchNoHighest = -32768;

/// A point's x16 disparity in 16 bits. Clamping changes no window: the range's ends, x16, lie
/// within +-16384 (minDisparity and numDisparities are at most 512 in magnitude) and the margin is
/// at most 512 px, so a value beyond +-32767 and its clamped value fall on the same side of the
/// range, with the same window.
LIDAR_SGM_HOST_DEVICE inline std::int16_t searchClamp16(int disparity16) {
  return static_cast<std::int16_t>(disparity16 < kSearchNoHighest ? kSearchNoHighest
                                   : disparity16 > kSearchNoLowest ? kSearchNoLowest
                                                                   : disparity16);
}

/// The window [first, first + count) of disparity indices of a pixel whose neighbourhood's points
/// span x16 disparities [low16, high16] (low16 > high16: no point): the whole range without a
/// point or when every point lies outside the range, else [floor(low) - margin, ceil(high) +
/// margin] clamped into the range, widened upward to a multiple of 16 indices and moved down as
/// far as needed to end inside the range.
LIDAR_SGM_HOST_DEVICE inline void searchWindowOf(int low16, int high16, int minDisparity, int numDisparities,
                                                 int margin, int& first, int& count) {
  first = 0;
  count = numDisparities;
  if (low16 > high16) return;
  const int below = floorDivide(low16, kDisparityScale) - margin - minDisparity;
  const int above = -floorDivide(-high16, kDisparityScale) + margin - minDisparity;  // ceil(high16 / 16)
  const int lowest = below > 0 ? below : 0;
  const int last = above < numDisparities - 1 ? above : numDisparities - 1;
  if (lowest > last) return;  // every point lies outside the range: nothing to narrow it to
  const int widened = (last - lowest + 1 + 15) / 16 * 16;
  count = widened < numDisparities ? widened : numDisparities;
  first = lowest < numDisparities - count ? lowest : numDisparities - count;
}

}  // namespace lidar_sgm
