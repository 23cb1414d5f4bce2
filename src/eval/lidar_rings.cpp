#include "lidar_rings.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lidar_sgm {
namespace eval {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
}

double quantile(std::vector<double>& sorted, double q) {
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const std::size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (pos - static_cast<double>(i)) * (sorted[j] - sorted[i]);
}

}  // namespace

std::vector<Eigen::Vector3f> toPoints(const pcl::PointCloud<pcl::PointXYZI>& scan) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.size());
  for (const pcl::PointXYZI& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

std::vector<Eigen::Vector3f> toPoints(const std::vector<io::KittiPoint>& scan) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.size());
  for (const io::KittiPoint& p : scan) points.emplace_back(p.x, p.y, p.z);
  return points;
}

std::vector<int> recoverRings(const std::vector<Eigen::Vector3f>& points, const RingRecoveryOptions& options) {
  if (!(options.wrapJumpDeg > 0.0 && options.wrapJumpDeg < 360.0)) {
    throw std::invalid_argument("RingRecoveryOptions: wrapJumpDeg must be in (0, 360)");
  }
  std::vector<int> rings(points.size(), 0);
  int ring = 0;
  std::size_t inRing = 0;
  bool havePrevious = false;
  double previous = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    const bool usable = p.allFinite() && (p.x() != 0.0f || p.y() != 0.0f);
    if (usable) {
      double azimuth = std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x())) * kRadToDeg;
      if (azimuth < 0.0) azimuth += 360.0;
      if (havePrevious && azimuth < previous - options.wrapJumpDeg && inRing >= options.minPointsPerRing) {
        ++ring;
        inRing = 0;
      }
      previous = azimuth;
      havePrevious = true;
    }
    rings[i] = ring;
    ++inRing;
  }
  return rings;
}

std::vector<int> recoverRings(const pcl::PointCloud<pcl::PointXYZI>& scan, const RingRecoveryOptions& options) {
  return recoverRings(toPoints(scan), options);
}

RingStatistics ringStatistics(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& rings) {
  if (points.size() != rings.size()) throw std::invalid_argument("ringStatistics: one ring per point expected");
  RingStatistics s;
  for (const int r : rings) s.rings = std::max(s.rings, r + 1);
  std::vector<std::vector<double>> elevations(static_cast<std::size_t>(s.rings));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite() || rings[i] < 0) continue;
    const double horizontal = std::hypot(static_cast<double>(p.x()), static_cast<double>(p.y()));
    elevations[static_cast<std::size_t>(rings[i])].push_back(std::atan2(static_cast<double>(p.z()), horizontal) *
                                                             kRadToDeg);
  }
  for (std::vector<double>& e : elevations) {
    s.counts.push_back(e.size());
    if (e.empty()) {
      s.medianElevationDeg.push_back(std::nan(""));
      s.spreadDeg.push_back(std::nan(""));
      continue;
    }
    std::sort(e.begin(), e.end());
    s.medianElevationDeg.push_back(quantile(e, 0.5));
    s.spreadDeg.push_back(quantile(e, 0.75) - quantile(e, 0.25));
  }
  std::vector<double> spreads;
  for (const double v : s.spreadDeg) {
    if (std::isfinite(v)) spreads.push_back(v);
  }
  s.medianSpreadDeg = median(spreads);
  std::vector<double> gaps;
  bool decreasing = s.rings > 1;
  bool increasing = s.rings > 1;
  for (int r = 0; r + 1 < s.rings; ++r) {
    const double a = s.medianElevationDeg[static_cast<std::size_t>(r)];
    const double b = s.medianElevationDeg[static_cast<std::size_t>(r) + 1];
    if (!(b < a)) decreasing = false;
    if (!(b > a)) increasing = false;
    gaps.push_back(std::abs(b - a));
  }
  s.monotonic = decreasing ? 1 : (increasing ? -1 : 0);
  if (!gaps.empty()) s.minGapDeg = *std::min_element(gaps.begin(), gaps.end());
  s.medianGapDeg = median(gaps);
  return s;
}

}  // namespace eval
}  // namespace lidar_sgm
