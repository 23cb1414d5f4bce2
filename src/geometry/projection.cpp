#include "lidar_sgm/geometry/projection.hpp"

#include <algorithm>
#include <cmath>
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

/// The occlusion window read one value per row instead of one per pixel: for each row of
/// `nearest` that holds a point, the largest x16 disparity over the halfWidth pixels left of each
/// pixel and over those right of it (kInvalidDisparity where none, or past the image's edge). A
/// KITTI frame's ~25,000 candidates each read 4 windows of 5 x 9 pixels otherwise.
class WindowMaxima {
 public:
  WindowMaxima(const Image<std::int16_t>& nearest, int halfWidth) : nearest_(nearest) {
    const int width = nearest.width();
    slot_.assign(static_cast<std::size_t>(nearest.height()), -1);
    int rows = 0;
    for (int y = 0; y < nearest.height(); ++y) {
      const std::int16_t* row = &nearest(0, y);
      if (std::any_of(row, row + width, [](std::int16_t d) { return d != kInvalidDisparity; })) slot_[y] = rows++;
    }
    left_.assign(static_cast<std::size_t>(rows) * width, kInvalidDisparity);
    right_.assign(left_.size(), kInvalidDisparity);
    for (int y = 0; y < nearest.height(); ++y) {
      if (slot_[y] < 0) continue;
      const std::int16_t* row = &nearest(0, y);
      std::int16_t* left = left_.data() + static_cast<std::size_t>(slot_[y]) * width;
      std::int16_t* right = right_.data() + static_cast<std::size_t>(slot_[y]) * width;
      // One shift at a time: each loop is a contiguous maximum the compiler vectorises.
      for (int k = 1; k <= halfWidth && k < width; ++k) {
        for (int x = k; x < width; ++x) left[x] = std::max(left[x], row[x - k]);
        for (int x = 0; x + k < width; ++x) right[x] = std::max(right[x], row[x + k]);
      }
    }
  }

  /// Whether a point nearer than `limit16` lies in rows [y0, y1] (clipped to the image), in the
  /// columns left of x (`left`), at x (`centre`) and right of x (`right`) within halfWidth.
  bool nearerIn(int x, int y0, int y1, bool left, bool centre, bool right, int limit16) const {
    const int width = nearest_.width();
    y0 = std::max(y0, 0);
    y1 = std::min(y1, nearest_.height() - 1);
    for (int y = y0; y <= y1; ++y) {
      const int s = slot_[static_cast<std::size_t>(y)];
      if (s < 0) continue;  // no point in the row
      const std::size_t at = static_cast<std::size_t>(s) * width + x;
      if ((left && left_[at] > limit16) || (centre && nearest_(x, y) > limit16) || (right && right_[at] > limit16)) {
        return true;
      }
    }
    return false;
  }

 private:
  const Image<std::int16_t>& nearest_;
  std::vector<int> slot_;  // per image row: its row in left_ and right_, -1 when it holds no point
  std::vector<std::int16_t> left_, right_;
};

/// The occlusion test of OcclusionFilter for one candidate: a nearer point (by more than the gap)
/// in the window of halfWidth x halfHeight pixels around it.
bool isOccluded(const Image<std::int16_t>& nearest, const WindowMaxima& maxima, const Candidate& c,
                const OcclusionFilter& f) {
  const double gap = std::max(f.minGap, f.relativeGap * c.disparity16 / kDisparityScale);
  const int limit16 = c.disparity16 + static_cast<int>(std::floor(gap * kDisparityScale));
  if (nearest(c.x, c.y) > limit16) return true;  // a nearer point in the very same pixel
  const int hh = f.halfHeight;
  if (!f.requireEnclosed) return maxima.nearerIn(c.x, c.y - hh, c.y + hh, true, true, true, limit16);
  // Enclosed: nearer points on both sides, above and below or left and right. A hidden point
  // projects inside the foreground's silhouette; a visible background point next to a
  // foreground edge has the foreground on one side only.
  const bool above = maxima.nearerIn(c.x, c.y - hh, c.y - 1, true, true, true, limit16);
  if (above && maxima.nearerIn(c.x, c.y + 1, c.y + hh, true, true, true, limit16)) return true;
  return maxima.nearerIn(c.x, c.y - hh, c.y + hh, true, false, false, limit16) &&
         maxima.nearerIn(c.x, c.y - hh, c.y + hh, false, false, true, limit16);
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
  const WindowMaxima maxima(nearest, filtered ? filter.halfWidth : 0);
  out.samples.reserve(candidates.size());
  out.sourceIndex.reserve(candidates.size());
  for (const Candidate& c : candidates) {
    if (filtered && isOccluded(nearest, maxima, c, filter)) {
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
