#include "lidar_sgm/geometry/projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

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

void validateOptions(const ProjectionOptions& o) {
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

/// The largest x16 disparity (nearest point) per pixel; kInvalidDisparity where none.
Image<std::int16_t> nearestPerPixel(int width, int height, const std::vector<Candidate>& candidates) {
  Image<std::int16_t> nearest(width, height, kInvalidDisparity);
  for (const Candidate& c : candidates) {
    std::int16_t& n = nearest(c.x, c.y);
    n = std::max<std::int16_t>(n, static_cast<std::int16_t>(c.disparity16));
  }
  return nearest;
}

/// The nearest disparity in each row segment [x - r, x + r] (a horizontal running max), so the
/// window test below costs O(halfHeight) per point instead of O(window area).
Image<std::int16_t> rowMax(const Image<std::int16_t>& nearest, int r) {
  Image<std::int16_t> out(nearest.width(), nearest.height(), kInvalidDisparity);
  for (int y = 0; y < nearest.height(); ++y) {
    for (int x = 0; x < nearest.width(); ++x) {
      std::int16_t m = kInvalidDisparity;
      for (int xx = std::max(0, x - r); xx <= std::min(nearest.width() - 1, x + r); ++xx) {
        m = std::max(m, nearest(xx, y));
      }
      out(x, y) = m;
    }
  }
  return out;
}

}  // namespace

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
  validateOptions(options);

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
  Image<std::int16_t> windowRowMax;
  if (filter.enabled && !candidates.empty()) {
    windowRowMax = rowMax(nearestPerPixel(out.width, out.height, candidates), filter.halfWidth);
  }
  out.samples.reserve(candidates.size());
  out.sourceIndex.reserve(candidates.size());
  for (const Candidate& c : candidates) {
    if (filter.enabled) {
      int nearest16 = kInvalidDisparity;
      for (int y = std::max(0, c.y - filter.halfHeight); y <= std::min(out.height - 1, c.y + filter.halfHeight); ++y) {
        nearest16 = std::max<int>(nearest16, windowRowMax(c.x, y));
      }
      const double gap = std::max(filter.minGap, filter.relativeGap * c.disparity16 / kDisparityScale);
      if (nearest16 - c.disparity16 > gap * kDisparityScale) {
        ++out.stats.occluded;
        continue;
      }
    }
    out.samples.push_back({c.x, c.y, c.disparity16});
    out.sourceIndex.push_back(c.source);
  }
  out.stats.kept = out.samples.size();
  return out;
}

}  // namespace geometry
}  // namespace lidar_sgm
