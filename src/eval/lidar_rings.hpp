#pragma once
// The laser (ring) index of each point of a KITTI velodyne scan, which has no ring field, for
// protocol P2's ring hold-out (EVALUATION.md).
//
// How KITTI stores a scan (measured on the two scans of kitti_stereo_lidar_calib_nogt): laser by
// laser, top laser first, each laser's points in increasing azimuth atan2(y, x), one revolution
// that starts and ends straight ahead (azimuth 0, where the cameras look and are triggered).
// A new laser therefore starts where the azimuth, taken in [0, 360) deg, falls back by more than
// 180 deg (from ~360 to ~0). The rule "a new laser starts where atan2 wraps from +180 to -180"
// (behind the car) finds 65 segments instead: each but the first and last holds the rear half of
// one laser and the front half of the next, with a ~0.45 deg elevation step at azimuth 0 inside
// the segment (e.g. densedepthmap_0000000001, points 76426 -> 76427: -11.71 -> -12.17 deg), i.e.
// right in the middle of the camera image. With the [0, 360) rule both scans give exactly 64
// rings whose median elevations fall strictly from ring 0 (~ +2.7 deg) to ring 63 (~ -23.7 deg),
// so no fallback (clustering by elevation) is needed.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace eval {

struct RingRecoveryOptions {
  /// A fall of the azimuth (in [0, 360) deg) by more than this starts a new ring.
  double wrapJumpDeg = 180.0;
  /// ...but only once the current ring has this many points: a laser has ~1,000-2,000 points in
  /// a KITTI scan, and azimuth jitter around 0 deg must not start a ring after a few points.
  std::size_t minPointsPerRing = 200;
};

/// The ring of each point (0 = the first laser stored: KITTI's top laser), in input order.
/// Points that are not finite or lie on the z axis (no azimuth) get the ring of the point before
/// them (0 at the start) and do not take part in the wrap detection.
std::vector<int> recoverRings(const std::vector<Eigen::Vector3f>& points, const RingRecoveryOptions& options = {});
std::vector<int> recoverRings(const pcl::PointCloud<pcl::PointXYZI>& scan, const RingRecoveryOptions& options = {});

/// The xyz of a cloud, in order (what recoverRings and geometry::project take).
std::vector<Eigen::Vector3f> toPoints(const pcl::PointCloud<pcl::PointXYZI>& scan);
/// The same for a scan read without PCL (io::readKittiScan).
std::vector<Eigen::Vector3f> toPoints(const std::vector<io::KittiPoint>& scan);

/// Elevation atan2(z, sqrt(x^2 + y^2)) per ring, to check a recovery.
struct RingStatistics {
  int rings = 0;                               ///< max ring + 1
  std::vector<std::size_t> counts;             ///< points per ring
  std::vector<double> medianElevationDeg;      ///< per ring
  std::vector<double> spreadDeg;               ///< per ring: interquartile range of the elevation
  double medianSpreadDeg = 0.0;                ///< median of spreadDeg over the rings
  double minGapDeg = 0.0;                      ///< smallest |median elevation step| between neighbouring rings
  double medianGapDeg = 0.0;
  /// +1: median elevations strictly decrease with the ring index (top laser first), -1: strictly
  /// increase, 0: neither.
  int monotonic = 0;
};
RingStatistics ringStatistics(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& rings);

}  // namespace eval
}  // namespace lidar_sgm
