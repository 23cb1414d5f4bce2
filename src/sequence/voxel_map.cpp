#include "lidar_sgm/sequence/voxel_map.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace sequence {
namespace {

/// Beyond 2^52 voxels a double no longer holds every integer: neighbouring voxels would merge.
constexpr double kMaxVoxelIndex = 4503599627370496.0;

std::int64_t voxelIndex(double coordinate, double leafSize) {
  const double index = std::floor(coordinate / leafSize);
  if (!(std::abs(index) < kMaxVoxelIndex)) {
    throw std::invalid_argument("a map point at " + std::to_string(coordinate) + " m is too far out for voxels of " +
                                std::to_string(leafSize) + " m");
  }
  return static_cast<std::int64_t>(index);
}

std::uint64_t mix(std::uint64_t h) {
  // splitmix64's finaliser: neighbouring voxels spread over the buckets.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

}  // namespace

std::size_t VoxelMap::KeyHash::operator()(const Key& k) const {
  const std::uint64_t h = mix(static_cast<std::uint64_t>(k.x)) ^ (mix(static_cast<std::uint64_t>(k.y)) * 3) ^
                          (mix(static_cast<std::uint64_t>(k.z)) * 7);
  return static_cast<std::size_t>(h);
}

VoxelMap::VoxelMap(double leafSize) : leafSize_(leafSize) {
  if (!(leafSize > 0.0) || !std::isfinite(leafSize)) {
    throw std::invalid_argument("the map's voxel size must be positive [m], got " + std::to_string(leafSize));
  }
}

void VoxelMap::add(const MapInput& cloud, const Eigen::Isometry3d& toWorld) {
  ++clouds_;
  colored_ += cloud.hasColor ? 1 : 0;
  confident_ += cloud.hasConfidence ? 1 : 0;
  for (const PointXYZRGBConfidence& point : cloud.points) {
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) continue;
    const Eigen::Vector3d p = toWorld * Eigen::Vector3d(point.x, point.y, point.z);
    const Key key{voxelIndex(p.x(), leafSize_), voxelIndex(p.y(), leafSize_), voxelIndex(p.z(), leafSize_)};
    const auto [where, inserted] = index_.try_emplace(key, voxels_.size());
    if (inserted) voxels_.emplace_back();
    Sums& sums = voxels_[where->second];
    sums.x += p.x();
    sums.y += p.y();
    sums.z += p.z();
    sums.r += point.r;
    sums.g += point.g;
    sums.b += point.b;
    sums.confidence += static_cast<double>(point.confidence);
    ++sums.count;
  }
}

pcl::PointCloud<PointXYZRGBConfidence> VoxelMap::points() const {
  pcl::PointCloud<PointXYZRGBConfidence> map;
  map.resize(voxels_.size());
  const bool color = hasColor();
  const bool confidence = hasConfidence();
  for (std::size_t i = 0; i < voxels_.size(); ++i) {
    const Sums& s = voxels_[i];
    const double n = static_cast<double>(s.count);
    PointXYZRGBConfidence& point = map[i];
    point.x = static_cast<float>(s.x / n);
    point.y = static_cast<float>(s.y / n);
    point.z = static_cast<float>(s.z / n);
    point.rgba = 0xff000000u;
    if (color) {
      // Rounded integer means: (sum + n/2) / n.
      point.r = static_cast<std::uint8_t>((s.r + s.count / 2) / s.count);
      point.g = static_cast<std::uint8_t>((s.g + s.count / 2) / s.count);
      point.b = static_cast<std::uint8_t>((s.b + s.count / 2) / s.count);
    }
    point.confidence = confidence ? static_cast<float>(s.confidence / n) : 0.0f;
  }
  map.width = static_cast<std::uint32_t>(map.size());
  map.height = 1;
  map.is_dense = true;
  return map;
}

}  // namespace sequence
}  // namespace lidar_sgm
