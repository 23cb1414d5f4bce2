#pragma once
// The merged map's accumulator: one point per occupied voxel, the centroid, mean color and mean
// confidence of the points that fell in it.

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>
#include <pcl/point_cloud.h>

#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace sequence {

/// A cloud to add: its points (non-finite ones are skipped) and which of their fields are real.
struct MapInput {
  pcl::PointCloud<PointXYZRGBConfidence> points;
  bool hasColor = false;
  bool hasConfidence = false;
};

/// A hash map over integer voxel indices with double sums, instead of pcl::VoxelGrid: VoxelGrid
/// packs the three indices of its bounding box into one 32-bit integer and refuses (or, in older
/// versions, wraps) when the box has more than 2^31 voxels, which a km-long drive at 0.1 m
/// exceeds; here each index is 64-bit, and memory grows with the occupied voxels only. Voxels are
/// kept in the order they were first occupied and sums are added in the order the clouds come,
/// so the same clouds in the same order give the same map, bit for bit.
class VoxelMap {
 public:
  /// Throws std::invalid_argument unless `leafSize` [m] is positive and finite.
  explicit VoxelMap(double leafSize);

  /// Adds `cloud`'s points, taken into the world by `toWorld`. Throws std::invalid_argument
  /// for a point whose voxel index does not fit (farther than 2^52 voxels).
  void add(const MapInput& cloud, const Eigen::Isometry3d& toWorld);

  /// The number of occupied voxels, the map's point count.
  std::size_t size() const { return voxels_.size(); }
  double leafSize() const { return leafSize_; }
  /// Whether every cloud added had colors (confidences): the map has them then.
  bool hasColor() const { return clouds_ > 0 && colored_ == clouds_; }
  bool hasConfidence() const { return clouds_ > 0 && confident_ == clouds_; }

  /// One point per voxel in first-occupied order: the centroid (rounded to float), the mean
  /// color (rounded to the nearest 8-bit value) and the mean confidence; fields the map does
  /// not have are 0.
  pcl::PointCloud<PointXYZRGBConfidence> points() const;

 private:
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  struct Sums {
    double x = 0, y = 0, z = 0, confidence = 0;
    std::uint64_t r = 0, g = 0, b = 0, count = 0;
  };

  double leafSize_;
  std::unordered_map<Key, std::size_t, KeyHash> index_;  ///< voxel -> position in voxels_
  std::vector<Sums> voxels_;
  std::size_t clouds_ = 0;
  std::size_t colored_ = 0;
  std::size_t confident_ = 0;
};

}  // namespace sequence
}  // namespace lidar_sgm
