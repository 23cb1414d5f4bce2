#pragma once
/// @file ply_reader.hpp  (private) A strict PLY reader for point clouds: the vertex element of an
/// ascii, binary_little_endian or binary_big_endian file, checked against the bytes present
/// before anything is allocated.
///
/// Why not PCL's PLYReader: hostile headers hit its asserts (a vertex count of 4294967297, a
/// list count of 0xFFFFFFFF) and "element vertex -40" made it loop forever.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <pcl/PCLPointCloud2.h>

namespace lidar_sgm {
namespace io {
namespace detail {

/// The vertices as PCL's blob (one field per scalar property, packed, host order; width = the
/// vertex count, height 1, or a camera element's viewportx x viewporty where that is the vertex
/// count) and, for a file PCL wrote from an organized cloud without a camera, its layout: a
/// range_grid element of num_cols x num_rows cells (obj_info), each the index of its vertex or
/// -1 for an empty cell.
struct PlyContent {
  pcl::PCLPointCloud2 blob;
  std::uint32_t gridWidth = 0;
  std::uint32_t gridHeight = 0;
  std::vector<std::int64_t> grid;  ///< empty: no layout
};

/// Parses the `size` bytes at `data`. The vertex element must come first, with scalar properties
/// (char ... double); other elements are walked through (in bounds) and ignored, except a
/// range_grid or camera, which give the layout as PCL's reader takes it. Throws std::runtime_error
/// "cannot read cloud '<source>': <problem>" for any header it does not understand, a vertex
/// count above `maxPoints` or beyond the bytes present, a list property in the vertex element,
/// or an ASCII line with the wrong number of values or a value that does not parse (naming the line).
PlyContent parsePly(const std::string& source, const std::uint8_t* data, std::size_t size, std::uint64_t maxPoints);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
