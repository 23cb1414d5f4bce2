#pragma once
/// @file pcd_writer.hpp  (private) PCD files in the three DATA forms, as PCL 1.13's PCDWriter
/// writes them (the same bytes for ASCII and binary; binary_compressed with liblzf, which PCL's
/// own LZF derives from: any PCD reader decompresses it), appended to an io::AtomicFile whose
/// every write is checked.
///
/// Why not PCL's writers: linking libpcl_io loads VTK, OpenNI and boost's libraries (68) into
/// every tool before main(), about 27 ms of each start (BENCHMARK.md, "Start-up"); its ASCII
/// writer never checks its stream (a full disk gave a truncated file and success), and its
/// binary one maps the file (a full disk raised SIGBUS).

#include <cstdint>
#include <string>
#include <vector>

#include <pcl/PCLPointCloud2.h>

#include "lidar_sgm/io/atomic_file.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {

/// The header up to and including "POINTS n\n" for `fields` (PCL's padding fields "_" left out),
/// VIEWPOINT at the origin. `rgbAsUnsigned`: TYPE U for a field named rgb (PCL's ASCII header,
/// whose values print rgb as an unsigned integer). Throws std::runtime_error for a field type
/// PCD cannot hold.
std::string pcdHeader(const std::vector<pcl::PCLPointField>& fields, std::uint32_t width, std::uint32_t height,
                      bool rgbAsUnsigned);

/// "DATA ascii": one line a point, its values separated by single spaces, floats with 9
/// significant digits (they read back exactly), rgb as an unsigned integer. `cloud.data` holds
/// width x height records of point_step bytes (checked by the caller).
void writeAsciiPcd(AtomicFile& out, const pcl::PCLPointCloud2& cloud);

/// "DATA binary_compressed": the fields packed one after the other, each field's values of all
/// points together (field-major, as PCL writes it), LZF-compressed, after the compressed and the
/// uncompressed size (two little-endian uint32). Throws std::runtime_error if the packed data is
/// too large for those sizes (PCL's limit: 1.5 x size <= 4 GiB).
void writeCompressedPcd(AtomicFile& out, const pcl::PCLPointCloud2& cloud);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
