#include "lidar_sgm/geometry/projection.hpp"

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

/// A point that survived the frustum and range checks, before the occlusion filter.
struct Candidate {
  int x;
  int y;
  int disparity16;
  std::size_t source;
};


/// The largest x16 disparity (nearest point) per pixel; kInvalidDisparity where none.
Image<std::int16_t> nearestPerPixel(int width, int height, const std::vector<Candidate>& candidates) {
  Image<std::int16_t> nearest(width, height, kInvalidDisparity);
  for (const Candidate& c : candidates) {
    std::int16_t& n = nearest(c.x, c.y);
    n = std::max<std::int16_t>(n, static_cast<std::int16_t>(c.disparity16));
  }
  return nearest;
}

/// The occlusion windows read on the rows that hold a point only: between a scan's lines (3-6 rows
/// apart on KITTI's images, OcclusionFilter::halfHeight) whole rows of a window hold none.
class OccupiedRows {
 public:
  explicit OccupiedRows(const Image<std::int16_t>& nearest) : nearest_(nearest) {
    occupied_.resize(static_cast<std::size_t>(nearest.height()));
    for (int y = 0; y < nearest.height(); ++y) {
      const std::int16_t* row = &nearest(0, y);
      occupied_[static_cast<std::size_t>(y)] =
          std::any_of(row, row + nearest.width(), [](std::int16_t d) { return d != kInvalidDisparity; }) ? 1 : 0;
    }
  }

  /// Whether a point nearer than `limit16` lies in the rectangle [x0, x1] x [y0, y1] (clipped to
  /// the image).
  bool nearerIn(int x0, int x1, int y0, int y1, int limit16) const {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, nearest_.width() - 1);
    y1 = std::min(y1, nearest_.height() - 1);
    for (int y = y0; y <= y1; ++y) {
      if (occupied_[static_cast<std::size_t>(y)] == 0) continue;
      const std::int16_t* row = &nearest_(0, y);
      for (int x = x0; x <= x1; ++x) {
        if (row[x] > limit16) return true;
      }
    }
    return false;
  }

 private:
  const Image<std::int16_t>& nearest_;
  std::vector<std::uint8_t> occupied_;  // per image row: whether any point projects into it
};

/// The occlusion test of OcclusionFilter for one candidate: a nearer point (by more than the gap)
/// in the window of halfWidth x halfHeight pixels around it.
bool isOccluded(const Image<std::int16_t>& nearest, const OccupiedRows& rows, const Candidate& c,
                const OcclusionFilter& f) {
  const double gap = std::max(f.minGap, f.relativeGap * c.disparity16 / kDisparityScale);
  const int limit16 = c.disparity16 + static_cast<int>(std::floor(gap * kDisparityScale));
  if (nearest(c.x, c.y) > limit16) return true;  // a nearer point in the very same pixel
  const int hw = f.halfWidth;
  const int hh = f.halfHeight;
  if (!f.requireEnclosed) return rows.nearerIn(c.x - hw, c.x + hw, c.y - hh, c.y + hh, limit16);
  // Enclosed: nearer points on both sides, above and below or left and right. A hidden point
  // projects inside the foreground's silhouette; a visible background point next to a
  // foreground edge has the foreground on one side only.
  if (rows.nearerIn(c.x - hw, c.x + hw, c.y - hh, c.y - 1, limit16) &&
      rows.nearerIn(c.x - hw, c.x + hw, c.y + 1, c.y + hh, limit16)) {
    return true;
  }
  return rows.nearerIn(c.x - hw, c.x - 1, c.y - hh, c.y + hh, limit16) &&
         rows.nearerIn(c.x + 1, c.x + hw, c.y - hh, c.y + hh, limit16);
}

}  // namespace

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
  calibration.validate();
  validate(options);

  ProjectedLidar out;
  out.width = calibration.width;
  out.height = calibration.height;
  out.stats.input = pointsLidar.size();

  const Eigen::Matrix3d R = calibration.T_cam_lidar.linear();
  const Eigen::Vector3d t = calibration.T_cam_lidar.translation();
  const double fb16 = calibration.focalBaseline() * kDisparityScale;
  std::vector<Candidate> candidates;
  candidates.reserve(pointsLidar.size() / 4);

  for (std::size_t i = 0; i < pointsLidar.size(); ++i) {
    const Eigen::Vector3d p = pointsLidar[i].cast<double>();
    if (!p.allFinite()) {
      ++out.stats.nonFinite;
      continue;
    }
    const Eigen::Vector3d c = R * p + t;
    if (!(c.z() > 0.0)) {
      ++out.stats.behindCamera;
      continue;
    }
    // Eq. 3 in x16 fixed point; the range check also keeps it inside int16 and >= 1/16 px.
    const double d16 = std::round(fb16 / c.z());
    if (c.z() < options.minDepth || c.z() > options.maxDepth || d16 < 1.0 ||
        d16 > std::numeric_limits<std::int16_t>::max()) {
      ++out.stats.outOfRange;
      continue;
    }
    // Pixel centres are at integer coordinates (KITTI/OpenCV), so the pixel is the rounded u, v.
    const double u = std::round(calibration.fx() * c.x() / c.z() + calibration.cx());
    const double v = std::round(calibration.fy() * c.y() / c.z() + calibration.cy());
    if (u < 0.0 || v < 0.0 || u >= calibration.width || v >= calibration.height) {
      ++out.stats.outsideImage;
      continue;
    }
    candidates.push_back({static_cast<int>(u), static_cast<int>(v), static_cast<int>(d16), i});
  }

  const OcclusionFilter& filter = options.occlusion;
  const bool filtered = filter.enabled && !candidates.empty();
  Image<std::int16_t> nearest;
  if (filtered) nearest = nearestPerPixel(out.width, out.height, candidates);
  const OccupiedRows rows(nearest);
  out.samples.reserve(candidates.size());
  out.sourceIndex.reserve(candidates.size());
  for (const Candidate& c : candidates) {
    if (filtered && isOccluded(nearest, rows, c, filter)) {
      ++out.stats.occluded;
      continue;
    }
    out.samples.push_back({c.x, c.y, c.disparity16});
    out.sourceIndex.push_back(c.source);
  }
  out.stats.kept = out.samples.size();
  return out;
}

}  // namespace geometry
}  // namespace lidar_sgm
