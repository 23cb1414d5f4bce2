#pragma once
/// @file projection.hpp  A LiDAR cloud into the left rectified image, as the sparse LiDAR
/// disparities that Eq. 4 compares against (d_P = f*b/z_P, Eq. 3).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace geometry {

/// The LiDAR sees the scene from another viewpoint than the left camera (KITTI: 0.27 m behind,
/// 0.08 m above), so some points that project into the image lie on surfaces the camera cannot
/// see: behind a foreground edge. Such a point carries the background's disparity into a
/// foreground pixel. The filter drops a point when other projected points in a small window
/// around it are clearly nearer (disparity above the point's by more than
/// max(minGap, relativeGap * d)) on two opposite sides: above and below, or left and right
/// (requireEnclosed), i.e. the point lies inside a nearer surface's silhouette. Measured on
/// synthetic frames with exact GT (BENCHMARK.md, "Occlusion filter"): it removes 44 % of the
/// projected points that are off by more than 1 px while dropping few correct ones; dropping on
/// any nearer neighbour removes more wrong points but more correct ones too, and scored lower.
struct OcclusionFilter {
  bool enabled = true;
  int halfWidth = 2;         ///< window half-size [px] in x; LiDAR columns are ~1 px apart
  int halfHeight = 4;        ///< in y; HDL-64 beam rows are 3-6 px apart in KITTI images
  double minGap = 2.0;       ///< [px] of disparity; a ground plane changes ~0.33 px per row
  double relativeGap = 0.1;  ///< fraction of the point's disparity
  /// Drop only points with nearer points on two opposite sides (above and below, or left and
  /// right) instead of anywhere in the window.
  bool requireEnclosed = true;
};

struct ProjectionOptions {
  /// Points nearer than this (z in the camera frame, [m]) are dropped as out of range; it
  /// also keeps the x16 disparity inside int16.
  double minDepth = 0.5;
  /// Points farther than this are dropped as out of range (a disparity below 1/16 px cannot
  /// be represented anyway).
  double maxDepth = std::numeric_limits<double>::infinity();
  OcclusionFilter occlusion;
};

/// What happened to the input points; every point is counted exactly once.
struct ProjectionStats {
  std::size_t input = 0;
  std::size_t nonFinite = 0;     ///< NaN or Inf coordinate
  std::size_t behindCamera = 0;  ///< z <= 0 in the camera frame
  std::size_t outOfRange = 0;    ///< z outside [minDepth, maxDepth] or disparity not in x16 range
  std::size_t outsideImage = 0;  ///< projects outside width x height
  std::size_t occluded = 0;      ///< dropped by the occlusion filter
  std::size_t kept = 0;
  std::string describe() const;  ///< "N in: K kept, ... behind camera, ..." for logs
};

/// The projected cloud: every kept point, its pixel and x16 disparity, and where it came from.
struct ProjectedLidar {
  std::vector<LidarSample> samples;       ///< kept points; (x, y) = rounded projection
  std::vector<std::size_t> sourceIndex;   ///< samples[i] came from input point sourceIndex[i]
  ProjectionStats stats;
  int width = 0;
  int height = 0;

  /// The per-pixel form the matcher takes (every point per pixel kept, for Eq. 4's 3x3 min).
  LidarPoints lidarPoints() const { return LidarPoints(width, height, samples); }
  /// One disparity per pixel, the nearest point winning (largest d); kInvalidDisparity elsewhere.
  Image<std::int16_t> sparseDisparity() const;
};

/// Throws std::invalid_argument naming the field when `options` are impossible (minDepth not
/// positive, maxDepth not above it, negative occlusion window or gaps).
void validate(const ProjectionOptions& options);

/// Projects `pointsLidar` (LiDAR frame, metres) into the left rectified image:
/// p_cam = T_cam_lidar * p, (u, v) = round(K * p_cam / z), d = f*b/z (Eq. 3) in x16.
/// `calibration` is validated first (std::invalid_argument).
ProjectedLidar project(const std::vector<Eigen::Vector3f>& pointsLidar,
                       const StereoCalibration& calibration, const ProjectionOptions& options = {});

}  // namespace geometry
}  // namespace lidar_sgm
