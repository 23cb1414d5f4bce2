#pragma once
/// @file sky_mask.hpp  Sky removal without ground truth, on the image grid: the bright, blank
/// region above the scan's top return that reaches the top of the image.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

/// What makes a pixel sky. Why: with the LiDAR the fused cost (Eq. 5) gives every pixel a
/// disparity and the left-right check is off, so the sky above the top beam (no return, a blank or
/// over-exposed patch of the left image where census matches anything) becomes a curtain of points.
struct SkyFilterOptions {
  bool enabled = true;
  /// A pixel is a candidate only when it lies more than `marginRows` rows above the highest LiDAR
  /// return of its column (taken over +-columnRadius columns): below it the scan measured.
  int marginRows = 2;
  /// Columns on each side that the highest return and the smallest LiDAR disparity are taken over
  /// (bridges dropouts between a beam's points).
  int columnRadius = 8;
  /// Far (off by default): a candidate whose disparity is below the smallest LiDAR disparity of
  /// the nearby columns by more than farSlack [px] lies farther than anything the LiDAR saw there.
  /// Off because it removes set-back facades above the top beam: on P3 clear (seeds 100-102) it
  /// removed 28.8 k right points for 23.8 k wrong ones and 0.3 k more sky (docs/RESULTS.md).
  bool farTest = false;
  double farSlack = 1.0;
  /// Bright and blank: the mean absolute gradient of the left image (8-bit levels per pixel,
  /// |dx| + |dy|) in a (2*textureRadius+1)^2 window below `textureThreshold` and the pixel at
  /// least `brightLevel` (8-bit; 16-bit images by their high byte; 256 = never). The sky is
  /// brighter than what stands under it (over-exposed: 255), and census finds nothing to match
  /// in a blank patch. A blank but darker facade is kept.
  int textureRadius = 3;
  double textureThreshold = 1.0;
  int brightLevel = 160;
};

/// Throws std::invalid_argument naming the first option out of range.
void validate(const SkyFilterOptions& options);

/// Invalidates (kInvalidDisparity) the sky: the candidate pixels that look like sky (bright and
/// blank, or far when farTest is on) and are 4-connected to the top row of the image, plus their
/// bright rim (candidates within textureRadius of them, whose texture window straddles the edge
/// of what stands in front). Real structure that reaches above the top beam (a facade, a tree)
/// breaks the connection, so it and a bright wall below it stay. Without samples nothing is
/// removed; an empty `left` leaves only the far test. Integer arithmetic; the result is a
/// connected component, independent of the visiting order. Returns the number of pixels it
/// invalidated.
std::size_t removeSky(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                      const GrayImageView& left, const SkyFilterOptions& options);

}  // namespace lidar_sgm
