#pragma once
/// @file binary_pcd_writer.hpp  (private) A fast "DATA binary" PCD writer.

#include <cstdint>
#include <string>

#include <pcl/PCLPointCloud2.h>

#include "lidar_sgm/io/atomic_file.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// Appends to `out` the width x height point records at `records` (each `layout.point_step`
/// bytes, with `layout.fields`; layout.data is not used) as PCD with "DATA binary", each point's
/// fields packed one after the other (no padding), viewpoint at the origin: the file PCL's
/// typed writer (PCDWriter::writeBinary<PointT>) makes, but for rgb's TYPE (F, the field's type,
/// as PCL's blob writer has it; its typed writer says U). Throws std::runtime_error with the
/// reason (`out` then removes what was written).
///
/// Why not PCL's blob writer: it maps the file (a full disk then kills the process with
/// SIGBUS) and copies whole point records, padding included (PointXYZRGB: 32 bytes, 16 of them padding); on a 424k-point KITTI cloud it took
/// 26-29 ms for 13.6 MB, this one 8 ms for 6.8 MB (docs/TOOLS.md, "Output formats").
void writeBinaryPcd(AtomicFile& out, const pcl::PCLPointCloud2& layout, const std::uint8_t* records);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
