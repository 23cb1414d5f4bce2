#pragma once
/// @file cloud_distance.hpp  A cloud held against a reference cloud in 3D, as reconstruction
/// benchmarks (Tanks and Temples, ETH3D) score one: precision = share of the cloud's points
/// within tau of the reference (nearest neighbour), completeness = share of the reference's
/// points within tau of the cloud, F-score = their harmonic mean; overall and per range band.
/// Nearest neighbours come from FLANN's kd-tree (the one pcl::KdTreeFLANN wraps, queried in
/// batches), exact (no approximation).
/// See docs/EVALUATION.md, "3D cloud-to-cloud score".
///
///   lidar_sgm::eval::CloudDistanceOptions options;
///   options.taus = {0.05, 0.1};                  // [m]
///   const auto score = lidar_sgm::eval::compareClouds(dense, survey, options);
///   double f = score.overall.scores[0].fScore;   // at tau 0.05 m
///   double far = score.bands.back().scores[0].completeness;  // 40-80 m

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace lidar_sgm {
namespace eval {

struct CloudDistanceOptions {
  /// [m] The distances within which a point counts as right; each > 0 and finite. One score per tau.
  std::vector<double> taus{0.05};
  /// [m] Range bands [edge_i, edge_i+1) by the distance of a point from `origin`; at least two
  /// edges, finite, >= 0 and increasing, or none (overall only). A reference point's band decides
  /// which band's completeness it counts in, a cloud point's band which band's precision.
  std::vector<double> bandEdges{0.0, 10.0, 20.0, 40.0, 80.0};
  /// Where ranges are measured from: the sensor (the clouds' frame origin by default).
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();
  /// Threads for the nearest-neighbour queries (>= 1); the result does not depend on it.
  int threads = 1;
};

/// The scores at one tau. A share that has no denominator (no point in a band) is NaN: "not
/// defined", never 0; F is NaN when either share is, 0 when both are 0.
struct CloudDistanceAtTau {
  double tau = 0;                ///< [m]
  long precisePoints = 0;        ///< cloud points within tau of the reference
  long coveredReferencePoints = 0;  ///< reference points within tau of the cloud
  double precision = 0;          ///< precisePoints / points
  double completeness = 0;       ///< coveredReferencePoints / referencePoints
  double fScore = 0;             ///< 2 P C / (P + C)
};

/// One range band's figures (or the overall ones). Distances are to the nearest neighbour in the
/// whole other cloud, whatever its band; the band only picks which points are counted.
struct CloudDistanceBand {
  double near = 0;               ///< [m] range [near, far); the overall figures: 0 and infinity
  double far = 0;
  long points = 0;               ///< judged cloud points in the band
  long referencePoints = 0;      ///< reference points in the band
  std::vector<CloudDistanceAtTau> scores;  ///< one per tau, in the order of CloudDistanceOptions::taus
  double meanDistance = 0;       ///< [m] cloud -> reference nearest-neighbour distance (accuracy)
  double medianDistance = 0;
  double meanReferenceDistance = 0;    ///< [m] reference -> cloud (how far the gaps are)
  double medianReferenceDistance = 0;
};

struct CloudDistanceScore {
  /// Every judged point and every reference point, whatever its range (also outside the bands).
  CloudDistanceBand overall;
  std::vector<CloudDistanceBand> bands;  ///< one per pair of consecutive band edges
  long skippedPoints = 0;           ///< cloud points with a NaN or infinite coordinate: not scored
  long skippedReferencePoints = 0;  ///< the same in the reference
  /// Finite cloud points left out of precision by the caller (ReferenceCloud::score's `judged`);
  /// they still count for completeness.
  long unjudgedPoints = 0;
};

/// A reference cloud with its kd-tree, built once and held against any number of clouds (the
/// evaluation scores every method of a frame against its one ground truth).
class ReferenceCloud {
 public:
  /// Points with a NaN or infinite coordinate are skipped (counted in skippedReferencePoints).
  /// Throws std::invalid_argument when `reference` is empty or has no finite point.
  explicit ReferenceCloud(const pcl::PointCloud<pcl::PointXYZ>& reference);
  ~ReferenceCloud();
  ReferenceCloud(ReferenceCloud&&) noexcept;
  ReferenceCloud& operator=(ReferenceCloud&&) noexcept;

  /// The finite reference points.
  std::size_t size() const;

  /// `cloud` against the reference. Non-finite points are skipped (skippedPoints). Throws
  /// std::invalid_argument naming the problem for an empty cloud, a cloud without a finite
  /// point, a tau that is not > 0 and finite, band edges that are not finite, >= 0 and
  /// increasing (or a single edge), or threads < 1.
  CloudDistanceScore score(const pcl::PointCloud<pcl::PointXYZ>& cloud, const CloudDistanceOptions& options) const;
  /// The same, with precision over the `judged` points of `cloud` only (indices into it), for a
  /// reference that covers part of the scene: a point where the reference has nothing cannot be
  /// judged (Tanks and Temples crops the cloud to the reference's region). Every finite point of
  /// `cloud` still serves completeness. An index outside the cloud is std::invalid_argument.
  CloudDistanceScore score(const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<int>& judged,
                           const CloudDistanceOptions& options) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// ReferenceCloud(reference).score(cloud, options): one cloud against one reference.
CloudDistanceScore compareClouds(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                 const pcl::PointCloud<pcl::PointXYZ>& reference, const CloudDistanceOptions& options);

/// Throws std::invalid_argument naming the problem when `options` is not valid (as score()).
void validate(const CloudDistanceOptions& options);

}  // namespace eval
}  // namespace lidar_sgm
