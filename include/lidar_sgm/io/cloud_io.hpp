#pragma once
/// @file cloud_io.hpp  Point cloud files: KITTI velodyne .bin, PCD and PLY in; PCD (binary,
/// binary-compressed or ASCII) and PLY (binary or ASCII) out, as PCL writes them (our own readers
/// and writers: the tools load no PCL io, VTK or OpenNI library).

#include <cstddef>
#include <cstdint>
#include <string>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/io/cloud_limits.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace io {

/// KITTI velodyne scan: float32 little-endian x, y, z, reflectance per point: readKittiScan()'s
/// points (kitti_bin.hpp, no PCL) as an unorganized cloud, dense when every x, y, z is finite.
/// Throws std::runtime_error naming the file when it is missing, or when its size is not a
/// multiple of 16 bytes (a truncated file is never read in part), or holds more than `maxPoints`
/// points (checked from its size, before reading). An empty file gives an empty cloud.
pcl::PointCloud<pcl::PointXYZI> readKittiBin(const std::string& path, std::uint64_t maxPoints = kMaxCloudPoints);
/// The same from the file's bytes already in memory (`size` bytes at `data`:
/// readKittiScanFromBuffer's points); `source` names them in messages.
pcl::PointCloud<pcl::PointXYZI> readKittiBinFromBuffer(const void* data, std::size_t size,
                                                       const std::string& source = "<buffer>");

/// PCD (ASCII, binary or binary-compressed) or PLY (ascii, binary little or big endian) with at
/// least x, y, z fields (float or double); intensity is read when there is an "intensity" (or
/// PLY "reflectance") field, else 0. RGB fields are accepted and ignored. Our own strict parsers
/// (not PCL's, which hostile files crashed): every header is checked against the file's size
/// before anything is allocated. Throws std::runtime_error naming the file and the problem for a
/// missing or unreadable file, a header it does not understand (duplicate or unknown keys,
/// inconsistent counts, unsupported types), more than `maxPoints` points, fewer bytes than
/// the header declares, an ASCII value that does not parse (naming the line), or missing x/y/z.
pcl::PointCloud<pcl::PointXYZI> readPcdOrPly(const std::string& path, std::uint64_t maxPoints = kMaxCloudPoints);
/// Checks that the .pcd or .ply file at `path` is whole: its header reads and its body holds
/// every point the header declares, as a write cut short (a full disk, a killed writer that
/// wrote in place) would not. Throws std::runtime_error "cannot read cloud 'path': problem".
void checkCloudFile(const std::string& path);
/// A PCD file's bytes (any of the three encodings) already in memory, read as readPcdOrPly()
/// reads a .pcd file (through the same parser); `source` names them in messages.
pcl::PointCloud<pcl::PointXYZI> readPcdFromBuffer(const void* data, std::size_t size,
                                                  const std::string& source = "<buffer>");
/// The same for a PLY file's bytes.
pcl::PointCloud<pcl::PointXYZI> readPlyFromBuffer(const void* data, std::size_t size,
                                                  const std::string& source = "<buffer>");

/// Every field of a PCD or PLY file's points as PCL's blob, through the same strict parsers as
/// readPcdOrPly (the same errors; no field is required): a PCD's fields as the file has them
/// (packed); a PLY's scalar vertex properties, its red, green, blue (and alpha) bytes packed into
/// PCL's rgb (rgba) field as PCL's PLY reader packs them, an organized PLY's cells in place with
/// NaN x, y, z where a cell is empty. For readers that need more than x, y, z and intensity
/// (colour, confidence); pcl::fromPCLPointCloud2 converts it to a typed cloud.
pcl::PCLPointCloud2 readCloudFields(const std::string& path, std::uint64_t maxPoints = kMaxCloudPoints);

/// Picks the reader from the extension: .bin, .pcd, .ply (case-insensitive); any other
/// extension is an error naming the accepted ones.
pcl::PointCloud<pcl::PointXYZI> readCloud(const std::string& path, std::uint64_t maxPoints = kMaxCloudPoints);

/// How writeCloud encodes the points. Measured on a 424k-point XYZRGB KITTI cloud (docs/TOOLS.md,
/// "Output formats"): binary PCD 8 ms / 6.8 MB, compressed 165 ms / 6.6 MB, ASCII about 1 s /
/// 19 MB.
enum class CloudFormat {
  Binary,      ///< PCD "DATA binary" (fields packed, no padding) or PLY binary_little_endian: the fastest
  Compressed,  ///< PCD "DATA binary_compressed" (PCL's LZF): ~3 % smaller for a dense cloud, 10-20x slower
  Ascii,       ///< text, the slowest and largest: floats with 9 significant digits (they read back
               ///< exactly), PCD and PLY
};

/// "binary", "compressed", "ascii".
std::string toString(CloudFormat format);
/// The inverse of toString(); std::invalid_argument naming the accepted names otherwise.
CloudFormat cloudFormatFromString(const std::string& name);

/// Throws std::invalid_argument when `path` cannot be written as `format`: an extension other
/// than .pcd or .ply (case-insensitive), or Compressed for a PLY file (PLY has no compressed
/// form). For callers that check their outputs before doing any work; writeCloud checks too.
void checkCloudOutput(const std::string& path, CloudFormat format);

/// Writes by extension (.pcd or .ply) in `format` (default: binary, the fastest). The file is
/// written to a temporary name in the same directory and renamed over `path` only when
/// complete. Throws std::runtime_error naming the file (also for a path checkCloudOutput refuses).
void writeCloud(const std::string& path, const pcl::PCLPointCloud2& cloud, CloudFormat format = CloudFormat::Binary);

namespace detail {
/// writeCloud for points that stay where they are: `layout` gives the fields, width, height and
/// point_step (its data is not used), `records` the `recordCount` point records.
void writeCloudRecords(const std::string& path, const pcl::PCLPointCloud2& layout, const std::uint8_t* records,
                       std::size_t recordCount, CloudFormat format);
}  // namespace detail

template <typename PointT>
void writeCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud, CloudFormat format = CloudFormat::Binary) {
  // The points are not copied into a PCLPointCloud2 first: for a 424k-point XYZRGB cloud that
  // copy took 14 ms in a fresh process, twice the binary write itself.
  pcl::PCLPointCloud2 layout;
  pcl::toPCLPointCloud2(pcl::PointCloud<PointT>(), layout);  // fields and point_step, no points
  layout.header = cloud.header;
  layout.width = cloud.width;
  layout.height = cloud.height;
  layout.row_step = layout.point_step * cloud.width;
  layout.is_dense = cloud.is_dense;
  detail::writeCloudRecords(path, layout, reinterpret_cast<const std::uint8_t*>(cloud.points.data()), cloud.size(),
                            format);
}

}  // namespace io
}  // namespace lidar_sgm
