#include "lidar_sgm/geometry/projection.hpp"
#include "geometry/projection_steps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace lidar_sgm {
namespace geometry {

namespace {

/// Whether a point nearer than `limit16` lies in the rectangle [x0, x1] x [y0, y1] (clipped to
/// the image), read on the occupied rows only.
bool nearerIn(ImageView<const std::int16_t> nearest, const std::uint8_t* occupied, int x0, int x1, int y0, int y1,
              int limit16) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, nearest.width - 1);
  y1 = std::min(y1, nearest.height - 1);
  for (int y = y0; y <= y1; ++y) {
    if (occupied[y] == 0) continue;
    const std::int16_t* row = nearest.row(y);
    for (int x = x0; x <= x1; ++x) {
      if (row[x] > limit16) return true;
    }
  }
  return false;
}

/// The occlusion test of OcclusionFilter for one candidate: a nearer point (by more than the gap)
/// in the window of halfWidth x halfHeight pixels around it.
bool isOccluded(ImageView<const std::int16_t> nearest, const std::uint8_t* occupied, const ProjectionCandidate& c,
                const OcclusionFilter& f) {
  const double gap = std::max(f.minGap, f.relativeGap * c.disparity16 / kDisparityScale);
  const int limit16 = c.disparity16 + static_cast<int>(std::floor(gap * kDisparityScale));
  if (nearest(c.x, c.y) > limit16) return true;  // a nearer point in the very same pixel
  const int hw = f.halfWidth;
  const int hh = f.halfHeight;
  if (!f.requireEnclosed) return nearerIn(nearest, occupied, c.x - hw, c.x + hw, c.y - hh, c.y + hh, limit16);
  // Enclosed: nearer points on both sides, above and below or left and right. A hidden point
  // projects inside the foreground's silhouette; a visible background point next to a
  // foreground edge has the foreground on one side only.
  if (nearerIn(nearest, occupied, c.x - hw, c.x + hw, c.y - hh, c.y - 1, limit16) &&
      nearerIn(nearest, occupied, c.x - hw, c.x + hw, c.y + 1, c.y + hh, limit16)) {
    return true;
  }
  return nearerIn(nearest, occupied, c.x - hw, c.x - 1, c.y - hh, c.y + hh, limit16) &&
         nearerIn(nearest, occupied, c.x + 1, c.x + hw, c.y - hh, c.y + hh, limit16);
}

}  // namespace

ProjectionPlan planProjection(const StereoCalibration& calibration, const ProjectionOptions& options) {
  calibration.validate();
  validate(options);
  ProjectionPlan plan;
  plan.R = calibration.T_cam_lidar.linear();
  plan.t = calibration.T_cam_lidar.translation();
  plan.fb16 = calibration.focalBaseline() * kDisparityScale;
  plan.fx = calibration.fx();
  plan.fy = calibration.fy();
  plan.cx = calibration.cx();
  plan.cy = calibration.cy();
  plan.width = calibration.width;
  plan.height = calibration.height;
  plan.minDepth = options.minDepth;
  plan.maxDepth = options.maxDepth;
  return plan;
}

void projectCandidates(const ProjectionPlan& plan, const std::vector<Eigen::Vector3f>& points, std::size_t begin,
                       std::size_t end, std::vector<ProjectionCandidate>& out, ProjectionStats& stats) {
  for (std::size_t i = begin; i < end; ++i) {
    const Eigen::Vector3d p = points[i].cast<double>();
    if (!p.allFinite()) {
      ++stats.nonFinite;
      continue;
    }
    const Eigen::Vector3d c = plan.R * p + plan.t;
    if (!(c.z() > 0.0)) {
      ++stats.behindCamera;
      continue;
    }
    // Eq. 3 in x16 fixed point; the range check also keeps it inside int16 and >= 1/16 px.
    const double d16 = std::round(plan.fb16 / c.z());
    if (c.z() < plan.minDepth || c.z() > plan.maxDepth || d16 < 1.0 ||
        d16 > std::numeric_limits<std::int16_t>::max()) {
      ++stats.outOfRange;
      continue;
    }
    // Pixel centres are at integer coordinates (KITTI/OpenCV), so the pixel is the rounded u, v.
    const double u = std::round(plan.fx * c.x() / c.z() + plan.cx);
    const double v = std::round(plan.fy * c.y() / c.z() + plan.cy);
    if (u < 0.0 || v < 0.0 || u >= plan.width || v >= plan.height) {
      ++stats.outsideImage;
      continue;
    }
    out.push_back({static_cast<int>(u), static_cast<int>(v), static_cast<int>(d16), i});
  }
}

void markNearest(const std::vector<ProjectionCandidate>& candidates, ImageView<std::int16_t> nearest) {
  for (const ProjectionCandidate& c : candidates) {
    std::int16_t& n = nearest(c.x, c.y);
    n = std::max<std::int16_t>(n, static_cast<std::int16_t>(c.disparity16));
  }
}

void occupiedRows(ImageView<const std::int16_t> nearest, int y0, int y1, std::uint8_t* occupied) {
  for (int y = y0; y < y1; ++y) {
    const std::int16_t* row = nearest.row(y);
    occupied[y] =
        std::any_of(row, row + nearest.width, [](std::int16_t d) { return d != kInvalidDisparity; }) ? 1 : 0;
  }
}

void keepAll(const std::vector<ProjectionCandidate>& candidates, std::vector<LidarSample>& samples,
             std::vector<std::size_t>& sourceIndex) {
  for (const ProjectionCandidate& c : candidates) {
    samples.push_back({c.x, c.y, c.disparity16});
    sourceIndex.push_back(c.source);
  }
}

std::size_t keepUnoccluded(const std::vector<ProjectionCandidate>& candidates, std::size_t begin, std::size_t end,
                           ImageView<const std::int16_t> nearest, const std::uint8_t* occupied,
                           const OcclusionFilter& filter, std::vector<LidarSample>& samples,
                           std::vector<std::size_t>& sourceIndex) {
  std::size_t occluded = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const ProjectionCandidate& c = candidates[k];
    if (isOccluded(nearest, occupied, c, filter)) {
      ++occluded;
      continue;
    }
    samples.push_back({c.x, c.y, c.disparity16});
    sourceIndex.push_back(c.source);
  }
  return occluded;
}

void validate(const ProjectionOptions& o) {
  if (!(o.minDepth > 0.0) || !std::isfinite(o.minDepth)) {
    throw std::invalid_argument("ProjectionOptions: minDepth must be positive and finite [m]");
  }
  if (!(o.maxDepth > o.minDepth)) {
    throw std::invalid_argument("ProjectionOptions: maxDepth must exceed minDepth");
  }
  const OcclusionFilter& f = o.occlusion;
  if (f.halfWidth < 0 || f.halfHeight < 0 || !(f.minGap >= 0.0) || !(f.relativeGap >= 0.0)) {
    throw std::invalid_argument(
        "OcclusionFilter: halfWidth, halfHeight, minGap and relativeGap must be >= 0");
  }
}

std::string ProjectionStats::describe() const {
  std::ostringstream s;
  s << input << " in: " << kept << " kept, " << behindCamera << " behind the camera, " << outsideImage
    << " outside the image, " << outOfRange << " out of range, " << occluded << " hidden from the camera, "
    << nonFinite << " NaN/Inf";
  return s.str();
}

Image<std::int16_t> ProjectedLidar::sparseDisparity() const {
  Image<std::int16_t> sparse(width, height, kInvalidDisparity);
  for (const LidarSample& s : samples) {
    std::int16_t& d = sparse(s.x, s.y);
    d = std::max<std::int16_t>(d, static_cast<std::int16_t>(s.disparity16));
  }
  return sparse;
}

ProjectedLidar project(const std::vector<Eigen::Vector3f>& pointsLidar, const StereoCalibration& calibration,
                       const ProjectionOptions& options) {
  const ProjectionPlan plan = planProjection(calibration, options);
  ProjectedLidar out;
  out.width = plan.width;
  out.height = plan.height;
  out.stats.input = pointsLidar.size();
  std::vector<ProjectionCandidate> candidates;
  candidates.reserve(pointsLidar.size() / 4);
  projectCandidates(plan, pointsLidar, 0, pointsLidar.size(), candidates, out.stats);

  const OcclusionFilter& filter = options.occlusion;
  out.samples.reserve(candidates.size());
  out.sourceIndex.reserve(candidates.size());
  if (filter.enabled && !candidates.empty()) {
    Image<std::int16_t> nearest(out.width, out.height, kInvalidDisparity);
    markNearest(candidates, nearest.view());
    std::vector<std::uint8_t> occupied(static_cast<std::size_t>(out.height));
    occupiedRows(nearest.view(), 0, out.height, occupied.data());
    out.stats.occluded = keepUnoccluded(candidates, 0, candidates.size(), nearest.view(), occupied.data(), filter,
                                        out.samples, out.sourceIndex);
  } else {
    keepAll(candidates, out.samples, out.sourceIndex);
  }
  out.stats.kept = out.samples.size();
  return out;
}

}  // namespace geometry
}  // namespace lidar_sgm
