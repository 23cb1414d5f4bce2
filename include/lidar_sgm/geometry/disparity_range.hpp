#pragma once
/// @file disparity_range.hpp  The disparity search range of a frame, taken from its LiDAR.
///
/// The paper searches a fixed 128 disparities, which a near object breaks (KITTI frame
/// stereo_rcnn_demo: a parked car at up to 163 px). The projected scan already says how near the
/// nearest surface is, so the range follows it:
///   dMax   = the largest LiDAR disparity once the `ignoredPoints` largest are set aside
///            (never more than `ignoredFraction` of the points): a near object of a few hundred
///            points counts, a handful of stray returns does not;
///   top    = dMax + max(marginPx, marginFraction * dMax): room for what is nearer than the
///            nearest point seen (between beams, below the lowest beam) and for the sub-pixel fit,
///            which needs the cost one step above the best;
///   numDisparities = top rounded up to the granularity (16, or 32 at scale 0.5), at least
///            `minNumDisparities`, at most `maxNumDisparities` (rounded down to the granularity).
/// minDisparity stays 0: surfaces farther than the LiDAR's reach (sky, far facades) have
/// disparities below the scan's smallest, and a positive minimum would force them onto wrong
/// ones, for a saving of a few of ~150 disparities.

#include <cstddef>
#include <string>
#include <vector>

#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace geometry {

/// The rule's numbers (the defaults are the ones measured in docs/RESULTS.md).
struct DisparityRangeRule {
  int ignoredPoints = 10;          ///< largest disparities set aside as strays, in [0, 10000]
  double ignoredFraction = 0.01;   ///< ... but never more than this fraction of the points, in [0, 0.5]
  double marginPx = 8.0;           ///< least margin above dMax [px], in [0, 512]
  double marginFraction = 0.05;    ///< margin as a fraction of dMax, in [0, 1]
  int minNumDisparities = 16;      ///< floor of the range, multiple of 16 in [16, 512]
  int maxNumDisparities = 256;     ///< cap of the range, multiple of 16 in [16, 512], >= the floor
};

/// An empty string when `rule` is valid; otherwise a message naming the offending field.
std::string validationError(const DisparityRangeRule& rule);

/// The range a frame was matched with.
struct DisparityRange {
  int minDisparity = 0;
  int numDisparities = 128;
  bool fromLidar = false;   ///< false: the fixed range (Fixed mode, or no LiDAR point)
  bool capped = false;      ///< the LiDAR asked for more than maxNumDisparities
  double lidarMax = 0.0;    ///< dMax, the robust largest LiDAR disparity [px] (0 without LiDAR)
  std::size_t points = 0;   ///< LiDAR points it was taken from
  /// "[0, 176) px from the LiDAR (max 163.4 px)" or "[0, 128) px (fixed)".
  std::string describe() const;
};

/// The search granularity of `params`: numDisparities must be a multiple of it (16; 32 at
/// scale 0.5, where half the range is searched in steps of 16).
int disparityGranularity(const Parameters& params);

/// The range for a frame whose projected scan is `samples` (x16 disparities). Without samples,
/// `fixed`'s minDisparity/numDisparities (fromLidar false). Otherwise minDisparity 0 and
/// numDisparities by the rule above, a multiple of disparityGranularity(fixed). Throws
/// std::invalid_argument naming the field when `rule` is invalid.
DisparityRange disparityRangeFromLidar(const std::vector<LidarSample>& samples, const Parameters& fixed,
                                       const DisparityRangeRule& rule = {});

}  // namespace geometry
}  // namespace lidar_sgm
