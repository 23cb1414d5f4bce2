#pragma once
// The merged map's files: a frame's dense cloud read back as written, the map written out.

#include <string>

#include "lidar_sgm/sequence/voxel_map.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace sequence {

/// A dense cloud as lidar_sgm_batch writes it (.pcd or .ply; x y z, and rgb and confidence when
/// present). Throws std::runtime_error naming the file when it cannot be read or has no x/y/z.
MapInput readFrameCloud(const std::string& path);

/// The map's points (VoxelMap::points()) with the fields the map has: x y z, then rgb and
/// confidence when it has them, written atomically (io::writeCloud's temporary file) in
/// `format`. Throws std::runtime_error naming the file.
void writeMapCloud(const std::string& path, const VoxelMap& map, io::CloudFormat format = io::CloudFormat::Binary);

}  // namespace sequence
}  // namespace lidar_sgm
