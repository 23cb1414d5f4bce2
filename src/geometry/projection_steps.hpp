#pragma once
// geometry::project (projection.hpp) in its steps, for a caller that splits the points and the
// candidates among threads (pipeline/fast/projection.cpp): projectCandidates on point ranges,
// their candidates concatenated in range order; markNearest over all of them; then
// keepUnoccluded on candidate ranges, their samples concatenated in range order. Each point and
// each candidate is decided by the same arithmetic whichever range holds it, and the nearest
// point per pixel is a maximum (its order does not matter): the result is project's for any split.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/geometry/projection.hpp"

namespace lidar_sgm {
namespace geometry {

/// A point that survived the frustum and range checks, before the occlusion filter.
struct ProjectionCandidate {
  int x;
  int y;
  int disparity16;
  std::size_t source;
};

/// The frame's constants of Eq. 3 and the pixel grid.
struct ProjectionPlan {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  double fb16 = 0.0;  // f*b in x16 disparity units
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  int width = 0, height = 0;
  double minDepth = 0.0, maxDepth = 0.0;
};

/// Validates the calibration and the options (project's checks and messages).
ProjectionPlan planProjection(const StereoCalibration& calibration, const ProjectionOptions& options);

/// Appends the candidates of points [begin, end) to `out` in point order and counts the points
/// dropped before the occlusion filter into `stats` (nonFinite, behindCamera, outOfRange,
/// outsideImage).
void projectCandidates(const ProjectionPlan& plan, const std::vector<Eigen::Vector3f>& points, std::size_t begin,
                       std::size_t end, std::vector<ProjectionCandidate>& out, ProjectionStats& stats);

/// Sets `nearest` (sized width x height, kInvalidDisparity everywhere) to the largest x16
/// disparity (nearest point) of the candidates in each pixel.
void markNearest(const std::vector<ProjectionCandidate>& candidates, ImageView<std::int16_t> nearest);

/// Per image row of `nearest`: 1 when any point projects into it. The occlusion windows read only
/// those rows: between a scan's lines (3-6 rows apart on KITTI's images) whole rows hold none.
void occupiedRows(ImageView<const std::int16_t> nearest, int y0, int y1, std::uint8_t* occupied);

/// Every candidate of `candidates`, appended in order to `samples` and `sourceIndex` (the filter off).
void keepAll(const std::vector<ProjectionCandidate>& candidates, std::vector<LidarSample>& samples,
             std::vector<std::size_t>& sourceIndex);

/// Candidates [begin, end) that the occlusion filter keeps, appended in order to `samples` and
/// `sourceIndex`; returns how many it dropped. `nearest` and `occupied` as set above.
std::size_t keepUnoccluded(const std::vector<ProjectionCandidate>& candidates, std::size_t begin, std::size_t end,
                           ImageView<const std::int16_t> nearest, const std::uint8_t* occupied,
                           const OcclusionFilter& filter, std::vector<LidarSample>& samples,
                           std::vector<std::size_t>& sourceIndex);

}  // namespace geometry
}  // namespace lidar_sgm
