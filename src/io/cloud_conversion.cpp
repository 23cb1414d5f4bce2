#include "cloud_conversion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "cloud_read_error.hpp"
#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

bool finiteXyz(const pcl::PointXYZI& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Bytes of one value in memory: the types a PCD file holds (datatypeSize), and a bool, which
// pcl::PCLPointCloud2 may carry but PCD does not.
std::size_t typeSize(std::uint8_t datatype) {
  return datatype == pcl::PCLPointField::BOOL ? sizeof(bool) : datatypeSize(datatype);
}

template <typename T>
float loadAs(const std::uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);  // fields need not be aligned
  if constexpr (std::is_same_v<T, double>) {
    return narrowToFloat(value);  // a double beyond float's range: the cast is undefined
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
    failCloudRead(path, "field '" + field.name + "' has an unsupported type (" + std::to_string(field.datatype) + ")");
  }
  const std::uint64_t end = static_cast<std::uint64_t>(field.offset) +
                            static_cast<std::uint64_t>(typeSize(field.datatype)) * std::max<std::uint64_t>(field.count, 1);
  if (end > blob.point_step) {
    failCloudRead(path, "field '" + field.name + "' lies outside the " + std::to_string(blob.point_step) +
                            "-byte point record");
  }
  return FieldReader{field.offset, load};
}

FieldReader coordinateReader(const std::string& path, const pcl::PCLPointCloud2& blob, const std::string& name) {
  const pcl::PCLPointField* field = findField(blob, name);
  if (field == nullptr) failCloudRead(path, "no '" + name + "' field (fields: " + fieldList(blob) + ")");
  if (field->datatype != pcl::PCLPointField::FLOAT32 && field->datatype != pcl::PCLPointField::FLOAT64) {
    failCloudRead(path, "field '" + name + "' has type " + datatypeName(field->datatype) +
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
  if (blob.point_step == 0) failCloudRead(path, "the header declares points of 0 bytes");
  if (rowStep < packedRow) failCloudRead(path, "the row step is smaller than width x point step");
  const std::uint64_t needed = rowStep * (blob.height - 1) + packedRow;
  if (blob.data.size() < needed) {
    failCloudRead(path, "the data holds " + std::to_string(blob.data.size()) + " bytes but the header declares " +
                            std::to_string(blob.width) + " x " + std::to_string(blob.height) + " points of " +
                            std::to_string(blob.point_step) + " bytes: truncated?");
  }
  return rowStep;
}

}  // namespace

pcl::PointCloud<pcl::PointXYZI> toXyzi(const std::string& path, const pcl::PCLPointCloud2& blob) {
  const std::uint64_t rowStep = checkedRowStep(path, blob);
  const FieldReader x = coordinateReader(path, blob, "x");
  const FieldReader y = coordinateReader(path, blob, "y");
  const FieldReader z = coordinateReader(path, blob, "z");
  const FieldReader intensity = intensityReader(path, blob);

  pcl::PointCloud<pcl::PointXYZI> cloud;
  reserveOnHugePages(cloud.points, static_cast<std::size_t>(blob.width) * blob.height);
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

pcl::PointCloud<pcl::PointXYZI> toXyzi(const std::vector<KittiPoint>& points) {
  pcl::PointCloud<pcl::PointXYZI> cloud;
  reserveOnHugePages(cloud.points, points.size());
  cloud.resize(points.size());
  cloud.width = static_cast<std::uint32_t>(cloud.size());  // resize(0) would leave height 0
  cloud.height = 1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    pcl::PointXYZI& p = cloud.points[i];
    p.x = points[i].x;
    p.y = points[i].y;
    p.z = points[i].z;
    p.intensity = points[i].intensity;
  }
  setDenseness(cloud);
  return cloud;
}

void setDenseness(pcl::PointCloud<pcl::PointXYZI>& cloud) {
  cloud.is_dense = std::all_of(cloud.points.begin(), cloud.points.end(), finiteXyz);
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
