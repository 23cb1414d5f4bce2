#pragma once
/// @file pcd_reader.hpp  (private) A strict PCD reader: the header is checked against the bytes
/// present before anything is allocated, then the body (ascii, binary, binary_compressed) is read.
///
/// Why not PCL's reader: fed hostile files it wrote out of bounds (readBodyASCII's
/// copyStringValue, readBodyBinary), trusted binary_compressed sizes (8 GB asked for by a
/// 100-byte file) and turned text that is not a number into 0 without a word.

#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Geometry>
#include <pcl/PCLPointCloud2.h>

namespace lidar_sgm {
namespace io {
namespace detail {

/// A PCD file's points as PCL's blob (fields packed in file order, no padding) and its VIEWPOINT.
struct PcdContent {
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
};

/// Parses the `size` bytes at `data`. The header needs FIELDS, SIZE, TYPE, WIDTH, HEIGHT, POINTS
/// and DATA (VERSION, COUNT, VIEWPOINT optional), each once; SIZE/TYPE/COUNT one per field;
/// TYPE I/U of 1, 2, 4 or 8 bytes or F of 4 or 8; POINTS = WIDTH x HEIGHT <= `maxPoints`.
/// Throws std::runtime_error "cannot read cloud '<source>': <problem>" otherwise, for a body
/// shorter than POINTS records, a compressed block whose sizes do not fit the file, or an ASCII
/// line with the wrong number of values or a value that does not parse (naming the line).
PcdContent parsePcd(const std::string& source, const std::uint8_t* data, std::size_t size, std::uint64_t maxPoints);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
