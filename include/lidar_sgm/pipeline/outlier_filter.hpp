#pragma once
/// @file outlier_filter.hpp  Isolated and flying points, on the image grid: a disparity with too
/// few neighbours of similar depth.

#include <cstddef>
#include <cstdint>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {

/// Why: a point that no neighbour pixel confirms at a similar depth is a lone wrong match, or a
/// "flying" point between a foreground edge and the background (the disparity of a pixel whose
/// window straddles the edge lies between the two surfaces, Eq. 3 puts it in mid-air). Real
/// surfaces, also a pole one pixel wide, have neighbours above and below at the same depth.
struct OutlierFilterOptions {
  bool enabled = true;
  /// The neighbourhood: (2*radius+1)^2 pixels around the point, the point excluded.
  int radius = 2;
  /// Similar depth: |d_q - d_p| <= max(minTolerance px, relativeTolerance * d_p), i.e. within
  /// about relativeTolerance of the point's depth (dz/z = dd/d by Eq. 3).
  double relativeTolerance = 0.05;
  double minTolerance = 0.5;
  /// A point with fewer similar neighbours than this is removed (a 1-pixel-wide vertical pole
  /// has 2*radius of them).
  int minNeighbours = 4;
};

/// Throws std::invalid_argument naming the first option out of range.
void validate(const OutlierFilterOptions& options);

/// Invalidates (kInvalidDisparity) the points with fewer than minNeighbours similar neighbours.
/// Every decision reads the input disparity (a copy), never an already filtered pixel, so the
/// result does not depend on the order of the pixels. Integer arithmetic. Returns the number of
/// pixels it invalidated.
std::size_t removeOutliers(ImageView<std::int16_t> disparity16, const OutlierFilterOptions& options);

}  // namespace lidar_sgm
