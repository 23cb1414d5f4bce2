#pragma once
/// @file ply_writer.hpp  (private) PLY files (ASCII and binary little-endian) laid out as PCL
/// 1.13's PLYWriter lays them out without its camera element: its header (comment, obj_info,
/// vertex properties, rgb/rgba as red green blue [alpha] bytes, an empty face element) and, for
/// an organized cloud, the range_grid element that keeps width x height. Appended to an
/// io::AtomicFile whose every write is checked. Why not PCL's writer: pcd_writer.hpp.
///
/// Points whose x is not finite are left out of the vertex list where PCL leaves them out
/// (ASCII; binary organized clouds, whose range_grid then says which pixels are empty). ASCII
/// floats have 9 significant digits, so that they read back exactly (PCL's ASCII PLY has 6).

#include <pcl/PCLPointCloud2.h>

#include "lidar_sgm/io/atomic_file.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// `cloud.data` holds width x height records of point_step bytes (checked by the caller).
/// Throws std::runtime_error for a field type PLY cannot hold.
void writePly(AtomicFile& out, const pcl::PCLPointCloud2& cloud, bool binary);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
