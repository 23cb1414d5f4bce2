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

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "binary_pcd_writer.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "pcd_reader.hpp"
#include "pcl_file_writer.hpp"
#include "ply_reader.hpp"

namespace lidar_sgm {
namespace io {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void failWrite(const std::string& path, const std::string& problem) {
  throw std::runtime_error("cannot write '" + path + "': " + problem);
}

// PCL's writers trust the blob's sizes; an inconsistent one would be written past its data.
void checkWritable(const std::string& path, const pcl::PCLPointCloud2& cloud) {
  if (cloud.fields.empty()) failWrite(path, "the cloud has no fields");
  const std::uint64_t expected = static_cast<std::uint64_t>(cloud.width) * cloud.height * cloud.point_step;
  if (cloud.data.size() != expected) {
    failWrite(path, "the cloud is inconsistent: " + std::to_string(cloud.data.size()) + " data bytes for " +
                        std::to_string(cloud.width) + " x " + std::to_string(cloud.height) + " points of " +
                        std::to_string(cloud.point_step) + " bytes");
  }
}

// Floats need 9 significant digits to read back exactly (PCL's default is 8).
constexpr int kAsciiPrecision = 9;

/// The cloud in `extension`'s file type and `format`, appended to `out`.
void writeAs(AtomicFile& out, const std::string& extension, CloudFormat format, const pcl::PCLPointCloud2& cloud) {
  const Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  const Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  if (extension == ".pcd" && format == CloudFormat::Binary) {
    detail::writeBinaryPcd(out, cloud, cloud.data.data());
    return;
  }
  if (extension == ".pcd" && format == CloudFormat::Compressed) {
    // The stream form: PCL's file form maps the file, and a full disk then raises SIGBUS.
    std::ostringstream bytes;
    if (pcl::PCDWriter().writeBinaryCompressed(bytes, cloud, origin, orientation) != 0) {
      throw std::runtime_error("PCL's compressed writer failed");
    }
    out.write(bytes.str());
    return;
  }
  const std::uint64_t points = std::uint64_t{cloud.width} * cloud.height;
  auto verify = [&](const std::uint8_t* bytes, std::size_t size) {
    try {
      if (extension == ".pcd") {
        const detail::PcdContent content = detail::parsePcd("", bytes, size, points);
        if (std::uint64_t{content.blob.width} * content.blob.height == points) return;
        throw std::runtime_error("it holds " + std::to_string(content.blob.width * content.blob.height) + " points");
      }
      detail::parsePly("", bytes, size, points);
    } catch (const std::exception& e) {
      throw std::runtime_error("PCL's writer made an incomplete file (" + std::string(e.what()) + ")");
    }
  };
  detail::writeThroughPcl(out, [&](const std::string& file) {
    if (extension == ".pcd") return pcl::PCDWriter().writeASCII(file, cloud, origin, orientation, kAsciiPrecision);
    // range_grid rather than PCL's "camera" element: PCL's own PLY reader reports each camera
    // property as "not handled" on stderr, while both keep an organized cloud's width x height.
    if (format == CloudFormat::Ascii) {
      return pcl::PLYWriter().writeASCII(file, cloud, origin, orientation, kAsciiPrecision, /*use_camera=*/false);
    }
    return pcl::PLYWriter().writeBinary(file, cloud, origin, orientation, /*use_camera=*/false);
  }, verify);
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
  if (extension == ".ply" && cloud.data.empty()) failWrite(path, "PCL cannot write an empty cloud as PLY (use .pcd)");
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
  // PCL's writers need the points in a PCLPointCloud2.
  pcl::PCLPointCloud2 blob = layout;
  blob.data.assign(records, records + recordCount * layout.point_step);
  writeCloud(path, blob, format);
}

}  // namespace detail

}  // namespace io
}  // namespace lidar_sgm
