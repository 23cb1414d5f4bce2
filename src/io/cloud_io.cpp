#include "lidar_sgm/io/cloud_io.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <vector>

#include "lidar_sgm/io/file_access.hpp"
#include "pcd_reader.hpp"
#include "ply_reader.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace fs = std::filesystem;
namespace {

constexpr std::uint64_t kKittiPointBytes = 4 * sizeof(float);  // x, y, z, reflectance

[[noreturn]] void failRead(const std::string& path, const std::string& problem) {
  throw std::runtime_error("cannot read cloud '" + path + "': " + problem);
}

void requireRegularFile(const std::string& path) {
  const std::string unreadable = unreadableFileReason(path);
  if (!unreadable.empty()) failRead(path, unreadable);
}

bool finiteXyz(const pcl::PointXYZI& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// is_dense is a promise to downstream code (it may skip NaN checks), so it is computed from the
// points and never copied from a file header.
void setDenseness(pcl::PointCloud<pcl::PointXYZI>& cloud) {
  cloud.is_dense = std::all_of(cloud.points.begin(), cloud.points.end(), finiteXyz);
}

// KITTI files are little-endian whatever the host; assembling the bytes keeps this portable.
float littleEndianFloat(const unsigned char* bytes) {
  const std::uint32_t bits = static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
                             (static_cast<std::uint32_t>(bytes[2]) << 16) |
                             (static_cast<std::uint32_t>(bytes[3]) << 24);
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::vector<unsigned char> readAllBytes(const std::string& path, std::uint64_t size) {
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in) failRead(path, "cannot open the file");
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto got = static_cast<std::uint64_t>(in.gcount());
  if (got != size) {
    failRead(path, "read error after " + std::to_string(got) + " of " + std::to_string(size) + " bytes");
  }
  return bytes;
}

// ---- PCLPointCloud2 -> PointXYZI ------------------------------------------------------------

const char* typeName(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: return "int8";
    case pcl::PCLPointField::UINT8: return "uint8";
    case pcl::PCLPointField::INT16: return "int16";
    case pcl::PCLPointField::UINT16: return "uint16";
    case pcl::PCLPointField::INT32: return "int32";
    case pcl::PCLPointField::UINT32: return "uint32";
    case pcl::PCLPointField::INT64: return "int64";
    case pcl::PCLPointField::UINT64: return "uint64";
    case pcl::PCLPointField::FLOAT32: return "float32";
    case pcl::PCLPointField::FLOAT64: return "float64";
    case pcl::PCLPointField::BOOL: return "bool";
    default: return "unknown";
  }
}

std::size_t typeSize(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
    case pcl::PCLPointField::UINT8:
    case pcl::PCLPointField::BOOL: return 1;
    case pcl::PCLPointField::INT16:
    case pcl::PCLPointField::UINT16: return 2;
    case pcl::PCLPointField::INT32:
    case pcl::PCLPointField::UINT32:
    case pcl::PCLPointField::FLOAT32: return 4;
    case pcl::PCLPointField::INT64:
    case pcl::PCLPointField::UINT64:
    case pcl::PCLPointField::FLOAT64: return 8;
    default: return 0;
  }
}

template <typename T>
float loadAs(const std::uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);  // fields need not be aligned
  if constexpr (std::is_same_v<T, double>) {
    return detail::narrowToFloat(value);  // a double beyond float's range: the cast is undefined
  } else {
    return static_cast<float>(value);
  }
}

using Loader = float (*)(const std::uint8_t*);

Loader loaderFor(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: return &loadAs<std::int8_t>;
    case pcl::PCLPointField::UINT8: return &loadAs<std::uint8_t>;
    case pcl::PCLPointField::BOOL: return &loadAs<std::uint8_t>;  // one byte, 0 or 1
    case pcl::PCLPointField::INT16: return &loadAs<std::int16_t>;
    case pcl::PCLPointField::UINT16: return &loadAs<std::uint16_t>;
    case pcl::PCLPointField::INT32: return &loadAs<std::int32_t>;
    case pcl::PCLPointField::UINT32: return &loadAs<std::uint32_t>;
    case pcl::PCLPointField::INT64: return &loadAs<std::int64_t>;
    case pcl::PCLPointField::UINT64: return &loadAs<std::uint64_t>;
    case pcl::PCLPointField::FLOAT32: return &loadAs<float>;
    case pcl::PCLPointField::FLOAT64: return &loadAs<double>;
    default: return nullptr;
  }
}

/// Where one field lives in each point record, and how to turn it into a float.
struct FieldReader {
  std::size_t offset = 0;
  Loader load = nullptr;

  float operator()(const std::uint8_t* point) const { return load(point + offset); }
};

const pcl::PCLPointField* findField(const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (const pcl::PCLPointField& field : blob.fields) {
    if (field.name == name) return &field;
  }
  return nullptr;
}

std::string fieldList(const pcl::PCLPointCloud2& blob) {
  std::string names;
  for (const pcl::PCLPointField& field : blob.fields) names += (names.empty() ? "" : " ") + field.name;
  return names.empty() ? "none" : names;
}

// A header is not trusted: a field that does not fit in the point record would read the next
// point's bytes (or past the end of the data).
FieldReader readerFor(const std::string& path, const pcl::PCLPointCloud2& blob, const pcl::PCLPointField& field) {
  const Loader load = loaderFor(field.datatype);
  if (load == nullptr) {
    failRead(path, "field '" + field.name + "' has an unsupported type (" + std::to_string(field.datatype) + ")");
  }
  const std::uint64_t end = static_cast<std::uint64_t>(field.offset) +
                            static_cast<std::uint64_t>(typeSize(field.datatype)) * std::max<std::uint64_t>(field.count, 1);
  if (end > blob.point_step) {
    failRead(path, "field '" + field.name + "' lies outside the " + std::to_string(blob.point_step) +
                       "-byte point record");
  }
  return FieldReader{field.offset, load};
}

FieldReader coordinateReader(const std::string& path, const pcl::PCLPointCloud2& blob, const std::string& name) {
  const pcl::PCLPointField* field = findField(blob, name);
  if (field == nullptr) failRead(path, "no '" + name + "' field (fields: " + fieldList(blob) + ")");
  if (field->datatype != pcl::PCLPointField::FLOAT32 && field->datatype != pcl::PCLPointField::FLOAT64) {
    failRead(path, "field '" + name + "' has type " + typeName(field->datatype) +
                       "; x, y, z must be float32 or float64");
  }
  return readerFor(path, blob, *field);
}

/// The intensity under its usual names (PCL "intensity", KITTI/PLY "reflectance", "i"); a
/// reader with no loader when the file has none.
FieldReader intensityReader(const std::string& path, const pcl::PCLPointCloud2& blob) {
  for (const char* name : {"intensity", "reflectance", "i"}) {
    if (const pcl::PCLPointField* field = findField(blob, name)) return readerFor(path, blob, *field);
  }
  return FieldReader{};
}

// Readers that hit a short body may still hand back a blob sized from the header; a cloud is
// only converted when every declared point is really there.
std::uint64_t checkedRowStep(const std::string& path, const pcl::PCLPointCloud2& blob) {
  const std::uint64_t packedRow = static_cast<std::uint64_t>(blob.width) * blob.point_step;
  const std::uint64_t rowStep = blob.row_step != 0 ? blob.row_step : packedRow;
  if (blob.width == 0 || blob.height == 0) return rowStep;
  if (blob.point_step == 0) failRead(path, "the header declares points of 0 bytes");
  if (rowStep < packedRow) failRead(path, "the row step is smaller than width x point step");
  const std::uint64_t needed = rowStep * (blob.height - 1) + packedRow;
  if (blob.data.size() < needed) {
    failRead(path, "the data holds " + std::to_string(blob.data.size()) + " bytes but the header declares " +
                       std::to_string(blob.width) + " x " + std::to_string(blob.height) + " points of " +
                       std::to_string(blob.point_step) + " bytes: truncated?");
  }
  return rowStep;
}

pcl::PointCloud<pcl::PointXYZI> toXyzi(const std::string& path, const pcl::PCLPointCloud2& blob) {
  const std::uint64_t rowStep = checkedRowStep(path, blob);
  const FieldReader x = coordinateReader(path, blob, "x");
  const FieldReader y = coordinateReader(path, blob, "y");
  const FieldReader z = coordinateReader(path, blob, "z");
  const FieldReader intensity = intensityReader(path, blob);

  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.resize(static_cast<std::size_t>(blob.width) * blob.height);
  cloud.width = blob.width;  // resize() leaves the cloud unorganized; keep the file's layout
  cloud.height = blob.height;
  cloud.header = blob.header;
  std::size_t i = 0;
  for (std::uint64_t row = 0; row < blob.height; ++row) {
    const std::uint8_t* record = blob.data.data() + row * rowStep;
    for (std::uint64_t col = 0; col < blob.width; ++col, ++i, record += blob.point_step) {
      pcl::PointXYZI& p = cloud.points[i];
      p.x = x(record);
      p.y = y(record);
      p.z = z(record);
      p.intensity = intensity.load != nullptr ? intensity(record) : 0.0f;
    }
  }
  setDenseness(cloud);
  return cloud;
}

// ---- our readers ----------------------------------------------------------------------------

pcl::PointCloud<pcl::PointXYZI> pcdFromBytes(const std::string& source, const unsigned char* data, std::size_t size,
                                             std::uint64_t maxPoints = kMaxCloudPoints) {
  const detail::PcdContent content = detail::parsePcd(source, data, size, maxPoints);
  pcl::PointCloud<pcl::PointXYZI> cloud = toXyzi(source, content.blob);
  cloud.sensor_origin_ = content.origin;
  cloud.sensor_orientation_ = content.orientation;
  return cloud;
}

// PCL's organized PLY: the vertices hold the valid points only, the range grid puts them in
// place; an empty cell is a NaN point, as PCL's reader makes it.
pcl::PointCloud<pcl::PointXYZI> plyFromBytes(const std::string& source, const unsigned char* data, std::size_t size,
                                             std::uint64_t maxPoints = kMaxCloudPoints) {
  const detail::PlyContent content = detail::parsePly(source, data, size, maxPoints);
  pcl::PointCloud<pcl::PointXYZI> vertices = toXyzi(source, content.blob);
  if (content.grid.empty()) return vertices;
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.resize(content.grid.size());
  cloud.width = content.gridWidth;
  cloud.height = content.gridHeight;
  for (std::size_t i = 0; i < content.grid.size(); ++i) {
    pcl::PointXYZI& p = cloud.points[i];
    if (content.grid[i] >= 0) {
      p = vertices.points[static_cast<std::size_t>(content.grid[i])];
    } else {
      p.x = p.y = p.z = p.intensity = std::numeric_limits<float>::quiet_NaN();
    }
  }
  setDenseness(cloud);
  return cloud;
}

/// The one KITTI .bin decoder, for files and buffers.
/// A .bin file's size, checked before its bytes are read: whole records, at most `maxPoints`.
void checkKittiBinSize(const std::string& source, std::uint64_t size, std::uint64_t maxPoints) {
  if (size % kKittiPointBytes != 0) {
    failRead(source, "size " + std::to_string(size) + " bytes is not a multiple of " +
                         std::to_string(kKittiPointBytes) + " (x, y, z, reflectance float32): truncated?");
  }
  if (size / kKittiPointBytes > maxPoints) {
    failRead(source, std::to_string(size / kKittiPointBytes) + " points is more than the limit of " +
                         std::to_string(maxPoints) + " points per scan");
  }
}

pcl::PointCloud<pcl::PointXYZI> kittiBinFromBytes(const std::string& source, const unsigned char* bytes,
                                                  std::uint64_t size, std::uint64_t maxPoints = kMaxCloudPoints) {
  checkKittiBinSize(source, size, maxPoints);
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.resize(static_cast<std::size_t>(size / kKittiPointBytes));
  cloud.width = static_cast<std::uint32_t>(cloud.size());  // resize(0) would leave height 0
  cloud.height = 1;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const unsigned char* record = bytes + i * kKittiPointBytes;
    pcl::PointXYZI& p = cloud.points[i];
    p.x = littleEndianFloat(record);
    p.y = littleEndianFloat(record + 4);
    p.z = littleEndianFloat(record + 8);
    p.intensity = littleEndianFloat(record + 12);
  }
  setDenseness(cloud);
  return cloud;
}

}  // namespace

pcl::PointCloud<pcl::PointXYZI> readKittiBin(const std::string& path, std::uint64_t maxPoints) {
  requireRegularFile(path);
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) failRead(path, ec.message());
  checkKittiBinSize(path, size, maxPoints);  // before reading: a huge file is not loaded to be refused
  const std::vector<unsigned char> bytes = readAllBytes(path, size);
  return kittiBinFromBytes(path, bytes.data(), size, maxPoints);
}

pcl::PointCloud<pcl::PointXYZI> readKittiBinFromBuffer(const void* data, std::size_t size,
                                                       const std::string& source) {
  if (data == nullptr && size != 0) failRead(source, "null data pointer for " + std::to_string(size) + " bytes");
  return kittiBinFromBytes(source, static_cast<const unsigned char*>(data), size);
}

pcl::PointCloud<pcl::PointXYZI> readPcdFromBuffer(const void* data, std::size_t size, const std::string& source) {
  if (size == 0) failRead(source, "the buffer is empty");
  if (data == nullptr) failRead(source, "null data pointer for " + std::to_string(size) + " bytes");
  return pcdFromBytes(source, static_cast<const unsigned char*>(data), size);
}

pcl::PointCloud<pcl::PointXYZI> readPcdOrPly(const std::string& path, std::uint64_t maxPoints) {
  requireRegularFile(path);
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") failRead(path, "expected a .pcd or .ply file");
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) failRead(path, ec.message());
  if (size == 0) failRead(path, "the file is empty");
  const std::vector<unsigned char> bytes = readAllBytes(path, size);
  if (extension == ".pcd") return pcdFromBytes(path, bytes.data(), bytes.size(), maxPoints);
  return plyFromBytes(path, bytes.data(), bytes.size(), maxPoints);
}

void checkCloudFile(const std::string& path) {
  requireRegularFile(path);
  const std::string extension = lowerExtension(path);
  if (extension != ".pcd" && extension != ".ply") failRead(path, "expected a .pcd or .ply file");
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) failRead(path, ec.message());
  if (size == 0) failRead(path, "the file is empty");
  const std::vector<unsigned char> bytes = readAllBytes(path, size);
  // The parsers check the body against the header (and every ASCII value): nothing is converted.
  if (extension == ".pcd") {
    detail::parsePcd(path, bytes.data(), bytes.size(), kMaxCloudPoints);
  } else {
    detail::parsePly(path, bytes.data(), bytes.size(), kMaxCloudPoints);
  }
}

pcl::PointCloud<pcl::PointXYZI> readPlyFromBuffer(const void* data, std::size_t size, const std::string& source) {
  if (size == 0) failRead(source, "the buffer is empty");
  if (data == nullptr) failRead(source, "null data pointer for " + std::to_string(size) + " bytes");
  return plyFromBytes(source, static_cast<const unsigned char*>(data), size);
}

pcl::PointCloud<pcl::PointXYZI> readCloud(const std::string& path, std::uint64_t maxPoints) {
  const std::string extension = lowerExtension(path);
  if (extension == ".bin") return readKittiBin(path, maxPoints);
  if (extension == ".pcd" || extension == ".ply") return readPcdOrPly(path, maxPoints);
  failRead(path, "unsupported extension '" + extension + "' (accepted: .bin, .pcd, .ply)");
}

}  // namespace io
}  // namespace lidar_sgm
