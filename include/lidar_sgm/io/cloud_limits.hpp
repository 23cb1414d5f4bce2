#pragma once
/// @file cloud_limits.hpp  The one point limit of every scan reader (KITTI .bin, PCD, PLY), in a
/// header of its own: the PCL-free KITTI reader (kitti_bin.hpp) and the PCL readers (cloud_io.hpp)
/// share it, and the tools' -max_points defaults to it.

#include <cstdint>

namespace lidar_sgm {
namespace io {

/// The most points a scan file may declare (KITTI's scans hold about 120 k; a 128-beam sensor
/// about 260 k per turn): a header asking for more is refused, naming this limit, before
/// anything is allocated. The file readers take another limit (`maxPoints`; the tools'
/// -max_points) for the rare file that legitimately holds more.
constexpr std::uint64_t kMaxCloudPoints = 50'000'000;

}  // namespace io
}  // namespace lidar_sgm
