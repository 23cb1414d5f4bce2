#include "lidar_sgm/eval/cloud_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>

namespace lidar_sgm {
namespace eval {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

bool isFinite(const pcl::PointXYZ& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// The finite points of `cloud` (an unorganized copy: FLANN indexes every point it is given).
Cloud::Ptr finitePoints(const Cloud& cloud) {
  Cloud::Ptr finite(new Cloud);
  finite->reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud) {
    if (isFinite(p)) finite->push_back(p);
  }
  return finite;
}

void checkCloud(const Cloud& cloud, const Cloud& finite, const char* what) {
  if (cloud.empty()) throw std::invalid_argument(std::string("cloud distance: the ") + what + " is empty");
  if (finite.empty()) {
    throw std::invalid_argument(std::string("cloud distance: the ") + what + " has no finite point (" +
                                std::to_string(cloud.size()) + " points, every one NaN or infinite)");
  }
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

/// FLANN's kd-tree, the one pcl::KdTreeFLANN builds (KDTreeSingleIndex, exact search), queried
/// in batches: pcl::KdTreeFLANN takes one point per call, and each call opens an OpenMP region
/// in PCL's library, which cost twice the search itself here (perf: 45 % of the time in libgomp
/// and futex calls). A leaf of 32 points built and searched ~25 % faster than PCL's 15 on a
/// KITTI-sized cloud; the neighbours are exact either way.
class PointTree {
 public:
  /// `points` must outlive the tree.
  explicit PointTree(const Cloud& points)
      : index_(flann::Matrix<float>(const_cast<float*>(&points[0].x), points.size(), 3, sizeof(pcl::PointXYZ)),
               flann::KDTreeSingleIndexParams(32)) {
    index_.buildIndex();
  }

  /// The distance [m] from each of `queries` to its nearest neighbour, `threads` ways (each
  /// query is independent, so the split cannot change a distance).
  std::vector<double> nearestDistances(const Cloud& queries, int threads) const {
    std::vector<double> distances(queries.size());
    const auto run = [&](std::size_t begin, std::size_t end) {
      if (begin >= end) return;
      const std::size_t n = end - begin;
      flann::Matrix<float> points(const_cast<float*>(&queries[begin].x), n, 3, sizeof(pcl::PointXYZ));
      std::vector<std::size_t> indices(n);
      std::vector<float> squared(n);
      flann::Matrix<std::size_t> indexMatrix(indices.data(), n, 1);
      flann::Matrix<float> squaredMatrix(squared.data(), n, 1);
      flann::SearchParams exact(flann::FLANN_CHECKS_UNLIMITED, 0.0f, false);
      index_.knnSearch(points, indexMatrix, squaredMatrix, 1, exact);
      for (std::size_t i = 0; i < n; ++i) distances[begin + i] = std::sqrt(static_cast<double>(squared[i]));
    };
    const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(threads), queries.size() / 4096 + 1);
    if (workers <= 1) {
      run(0, queries.size());
      return distances;
    }
    std::vector<std::thread> pool;
    const std::size_t chunk = (queries.size() + workers - 1) / workers;
    for (std::size_t w = 0; w < workers; ++w) {
      const std::size_t begin = std::min(queries.size(), w * chunk);
      pool.emplace_back(run, begin, std::min(queries.size(), begin + chunk));
    }
    for (std::thread& t : pool) t.join();
    return distances;
  }

 private:
  flann::KDTreeSingleIndex<flann::L2_Simple<float>> index_;
};

/// The band index of `range` [m], or -1 outside every band.
int bandOf(double range, const std::vector<double>& edges) {
  if (edges.size() < 2 || range < edges.front() || !(range < edges.back())) return -1;
  return static_cast<int>(std::upper_bound(edges.begin(), edges.end(), range) - edges.begin()) - 1;
}

double ratio(long numerator, long denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / static_cast<double>(denominator) : kUndefined;
}

double mean(const std::vector<double>& values) {
  if (values.empty()) return kUndefined;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

/// For an even count the mean of the two middle values (as the reports' medians).
double median(std::vector<double> values) {
  if (values.empty()) return kUndefined;
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
  const double upper = values[middle];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (*std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle)) + upper);
}

/// The figures of one band from its points' nearest-neighbour distances.
CloudDistanceBand bandFigures(double near, double far, const std::vector<double>& distances,
                              const std::vector<double>& referenceDistances, const std::vector<double>& taus) {
  CloudDistanceBand band;
  band.near = near;
  band.far = far;
  band.points = static_cast<long>(distances.size());
  band.referencePoints = static_cast<long>(referenceDistances.size());
  for (double tau : taus) {
    CloudDistanceAtTau s;
    s.tau = tau;
    s.precisePoints = std::count_if(distances.begin(), distances.end(), [tau](double d) { return d <= tau; });
    s.coveredReferencePoints =
        std::count_if(referenceDistances.begin(), referenceDistances.end(), [tau](double d) { return d <= tau; });
    s.precision = ratio(s.precisePoints, band.points);
    s.completeness = ratio(s.coveredReferencePoints, band.referencePoints);
    const double sum = s.precision + s.completeness;  // NaN when either is
    s.fScore = std::isnan(sum) ? kUndefined : sum > 0.0 ? 2.0 * s.precision * s.completeness / sum : 0.0;
    band.scores.push_back(s);
  }
  band.meanDistance = mean(distances);
  band.medianDistance = median(distances);
  band.meanReferenceDistance = mean(referenceDistances);
  band.medianReferenceDistance = median(referenceDistances);
  return band;
}

double rangeOf(const pcl::PointXYZ& p, const Eigen::Vector3f& origin) {
  return (p.getVector3fMap() - origin).cast<double>().norm();
}

}  // namespace

void validate(const CloudDistanceOptions& options) {
  if (options.taus.empty()) throw std::invalid_argument("cloud distance: no tau given");
  for (double tau : options.taus) {
    if (!(tau > 0.0 && std::isfinite(tau))) {
      throw std::invalid_argument("cloud distance: tau " + number(tau) + " is not > 0 and finite [m]");
    }
  }
  const std::vector<double>& edges = options.bandEdges;
  if (edges.size() == 1) {
    throw std::invalid_argument("cloud distance: one band edge (" + number(edges[0]) +
                                ") makes no band; give at least two, or none");
  }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (!(edges[i] >= 0.0 && std::isfinite(edges[i]))) {
      throw std::invalid_argument("cloud distance: band edge " + number(edges[i]) + " is not >= 0 and finite [m]");
    }
    if (i > 0 && !(edges[i] > edges[i - 1])) {
      throw std::invalid_argument("cloud distance: band edges must increase (" + number(edges[i]) + " after " +
                                  number(edges[i - 1]) + ")");
    }
  }
  if (options.threads < 1) throw std::invalid_argument("cloud distance: threads must be >= 1");
}

struct ReferenceCloud::Impl {
  Cloud::Ptr points;
  std::unique_ptr<PointTree> tree;
  long skipped = 0;
};

ReferenceCloud::ReferenceCloud(const Cloud& reference) : impl_(new Impl) {
  impl_->points = finitePoints(reference);
  checkCloud(reference, *impl_->points, "reference cloud");
  impl_->skipped = static_cast<long>(reference.size() - impl_->points->size());
  impl_->tree = std::make_unique<PointTree>(*impl_->points);
}

ReferenceCloud::~ReferenceCloud() = default;
ReferenceCloud::ReferenceCloud(ReferenceCloud&&) noexcept = default;
ReferenceCloud& ReferenceCloud::operator=(ReferenceCloud&&) noexcept = default;

std::size_t ReferenceCloud::size() const { return impl_->points->size(); }

CloudDistanceScore ReferenceCloud::score(const Cloud& cloud, const CloudDistanceOptions& options) const {
  std::vector<int> every(cloud.size());
  for (std::size_t i = 0; i < every.size(); ++i) every[i] = static_cast<int>(i);
  return score(cloud, every, options);
}

CloudDistanceScore ReferenceCloud::score(const Cloud& cloud, const std::vector<int>& judged,
                                         const CloudDistanceOptions& options) const {
  validate(options);
  const Cloud::Ptr finite = finitePoints(cloud);
  checkCloud(cloud, *finite, "cloud");
  CloudDistanceScore result;
  result.skippedPoints = static_cast<long>(cloud.size() - finite->size());
  result.skippedReferencePoints = impl_->skipped;

  // Precision: each judged finite point to its nearest reference point.
  Cloud judgedPoints;
  judgedPoints.reserve(judged.size());
  for (int i : judged) {
    if (i < 0 || static_cast<std::size_t>(i) >= cloud.size()) {
      throw std::invalid_argument("cloud distance: judged index " + std::to_string(i) + " is outside the cloud (" +
                                  std::to_string(cloud.size()) + " points)");
    }
    if (isFinite(cloud[static_cast<std::size_t>(i)])) judgedPoints.push_back(cloud[static_cast<std::size_t>(i)]);
  }
  result.unjudgedPoints = static_cast<long>(finite->size()) - static_cast<long>(judgedPoints.size());
  const std::vector<double> distances = impl_->tree->nearestDistances(judgedPoints, options.threads);
  // Completeness: each reference point to its nearest point of the whole cloud.
  const PointTree cloudTree(*finite);
  const std::vector<double> referenceDistances = cloudTree.nearestDistances(*impl_->points, options.threads);

  const std::vector<double>& edges = options.bandEdges;
  const std::size_t bands = edges.size() < 2 ? 0 : edges.size() - 1;
  std::vector<std::vector<double>> bandDistances(bands), bandReferenceDistances(bands);
  for (std::size_t i = 0; i < judgedPoints.size(); ++i) {
    const int band = bandOf(rangeOf(judgedPoints[i], options.origin), edges);
    if (band >= 0) bandDistances[static_cast<std::size_t>(band)].push_back(distances[i]);
  }
  for (std::size_t i = 0; i < impl_->points->size(); ++i) {
    const int band = bandOf(rangeOf((*impl_->points)[i], options.origin), edges);
    if (band >= 0) bandReferenceDistances[static_cast<std::size_t>(band)].push_back(referenceDistances[i]);
  }
  result.overall =
      bandFigures(0.0, std::numeric_limits<double>::infinity(), distances, referenceDistances, options.taus);
  for (std::size_t b = 0; b < bands; ++b) {
    result.bands.push_back(
        bandFigures(edges[b], edges[b + 1], bandDistances[b], bandReferenceDistances[b], options.taus));
  }
  return result;
}

CloudDistanceScore compareClouds(const Cloud& cloud, const Cloud& reference, const CloudDistanceOptions& options) {
  validate(options);  // before the reference's tree is built
  return ReferenceCloud(reference).score(cloud, options);
}

}  // namespace eval
}  // namespace lidar_sgm
