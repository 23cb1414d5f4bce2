// The cloud writers of cloud_io.hpp: every format through io::AtomicFile, so that every byte
// written is checked, the file synced and its size checked before it is renamed into place.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

#include "binary_pcd_writer.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "pcd_writer.hpp"
#include "ply_writer.hpp"

namespace lidar_sgm {
namespace io {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void failWrite(const std::string& path, const std::string& problem) {
  throw std::runtime_error("cannot write '" + path + "': " + problem);
}

// The writers trust the blob's sizes; an inconsistent one would be read past its data.
void checkWritable(const std::string& path, const pcl::PCLPointCloud2& cloud) {
  if (cloud.fields.empty()) failWrite(path, "the cloud has no fields");
  const std::uint64_t expected = static_cast<std::uint64_t>(cloud.width) * cloud.height * cloud.point_step;
  if (cloud.data.size() != expected) {
    failWrite(path, "the cloud is inconsistent: " + std::to_string(cloud.data.size()) + " data bytes for " +
                        std::to_string(cloud.width) + " x " + std::to_string(cloud.height) + " points of " +
                        std::to_string(cloud.point_step) + " bytes");
  }
}

/// The cloud in `extension`'s file type and `format`, appended to `out`.
void writeAs(AtomicFile& out, const std::string& extension, CloudFormat format, const pcl::PCLPointCloud2& cloud) {
  if (extension == ".pcd") {
    switch (format) {
      case CloudFormat::Binary: detail::writeBinaryPcd(out, cloud, cloud.data.data()); return;
      case CloudFormat::Compressed: detail::writeCompressedPcd(out, cloud); return;
      case CloudFormat::Ascii: detail::writeAsciiPcd(out, cloud); return;
    }
  }
  detail::writePly(out, cloud, /*binary=*/format != CloudFormat::Ascii);
}

// Refusals of checkCloudOutput are write errors here (std::runtime_error, as every writeCloud error).
std::string checkedExtension(const std::string& path, CloudFormat format) {
  try {
    checkCloudOutput(path, format);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  return lowerExtension(path);
}

/// Runs `write(file)` on an AtomicFile of `path` and commits it: a failure anywhere replaces
/// nothing and leaves nothing, and says "cannot write 'path': reason".
template <typename Write>
void writeAtomically(const std::string& path, Write write) {
  AtomicFile file(path);
  try {
    write(file);
  } catch (const std::exception& e) {
    const std::string prefix = "cannot write '" + path + "': ";
    const std::string what = e.what();
    if (what.rfind(prefix, 0) == 0) throw;  // AtomicFile's own, already naming the path
    failWrite(path, what);
  }
  file.commit();
}

}  // namespace

std::string toString(CloudFormat format) {
  switch (format) {
    case CloudFormat::Binary: return "binary";
    case CloudFormat::Compressed: return "compressed";
    case CloudFormat::Ascii: return "ascii";
  }
  return "unknown";
}

CloudFormat cloudFormatFromString(const std::string& name) {
  for (CloudFormat format : {CloudFormat::Binary, CloudFormat::Compressed, CloudFormat::Ascii}) {
    if (toString(format) == name) return format;
  }
  throw std::invalid_argument("unknown cloud format '" + name + "': must be binary, compressed or ascii");
}

void checkCloudOutput(const std::string& path, CloudFormat format) {
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") {
    throw std::invalid_argument("cannot write '" + path + "': unsupported extension '" + extension +
                                "' (accepted: .pcd, .ply)");
  }
  if (extension == ".ply" && format == CloudFormat::Compressed) {
    throw std::invalid_argument("cannot write '" + path +
                                "' compressed: PLY has no compressed form (write a .pcd, or a binary or ascii PLY)");
  }
}

void writeCloud(const std::string& path, const pcl::PCLPointCloud2& cloud, CloudFormat format) {
  const std::string extension = checkedExtension(path, format);
  checkWritable(path, cloud);
  writeAtomically(path, [&](AtomicFile& file) { writeAs(file, extension, format, cloud); });
}

namespace detail {

void writeCloudRecords(const std::string& path, const pcl::PCLPointCloud2& layout, const std::uint8_t* records,
                       std::size_t recordCount, CloudFormat format) {
  const std::string extension = checkedExtension(path, format);
  if (recordCount != static_cast<std::uint64_t>(layout.width) * layout.height) {
    failWrite(path, "the cloud is inconsistent: " + std::to_string(recordCount) + " points for " +
                        std::to_string(layout.width) + " x " + std::to_string(layout.height));
  }
  if (extension == ".pcd" && format == CloudFormat::Binary) {
    if (layout.fields.empty()) failWrite(path, "the cloud has no fields");
    writeAtomically(path, [&](AtomicFile& file) { writeBinaryPcd(file, layout, records); });
    return;
  }
  // The other writers take the points in a PCLPointCloud2.
  pcl::PCLPointCloud2 blob = layout;
  blob.data.assign(records, records + recordCount * layout.point_step);
  writeCloud(path, blob, format);
}

}  // namespace detail

}  // namespace io
}  // namespace lidar_sgm
