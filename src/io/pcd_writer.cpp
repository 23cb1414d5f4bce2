#include "pcd_writer.hpp"

#include <lzf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "field_text.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

char typeLetter(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
    case pcl::PCLPointField::INT16:
    case pcl::PCLPointField::INT32:
    case pcl::PCLPointField::INT64: return 'I';
    case pcl::PCLPointField::UINT8:
    case pcl::PCLPointField::UINT16:
    case pcl::PCLPointField::UINT32:
    case pcl::PCLPointField::UINT64: return 'U';
    case pcl::PCLPointField::FLOAT32:
    case pcl::PCLPointField::FLOAT64: return 'F';
    default: return '?';
  }
}

std::uint32_t countOf(const pcl::PCLPointField& field) { return std::max<std::uint32_t>(field.count, 1); }

std::vector<pcl::PCLPointField> realFields(const pcl::PCLPointCloud2& cloud) {
  std::vector<pcl::PCLPointField> fields;
  for (const pcl::PCLPointField& field : cloud.fields) {
    if (field.name != "_") fields.push_back(field);  // PCL's name for padding
  }
  return fields;
}

}  // namespace

std::string pcdHeader(const std::vector<pcl::PCLPointField>& fields, std::uint32_t width, std::uint32_t height,
                      bool rgbAsUnsigned) {
  std::string names, sizes, types, counts;
  for (const pcl::PCLPointField& field : fields) {
    if (field.name == "_") continue;
    const int size = static_cast<int>(datatypeSize(field.datatype));
    if (size == 0) {
      throw std::runtime_error("field '" + field.name + "' has a type PCD cannot hold (" +
                               std::to_string(field.datatype) + ")");
    }
    names += " " + field.name;
    sizes += " " + std::to_string(size);
    types += ' ';
    types += rgbAsUnsigned && field.name == "rgb" ? 'U' : typeLetter(field.datatype);
    counts += " " + std::to_string(countOf(field));
  }
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + names + "\nSIZE" + sizes + "\nTYPE" +
         types + "\nCOUNT" + counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
         "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(std::uint64_t{width} * height) + "\n";
}

void writeAsciiPcd(AtomicFile& out, const pcl::PCLPointCloud2& cloud) {
  const std::vector<pcl::PCLPointField> fields = realFields(cloud);
  out.write(pcdHeader(fields, cloud.width, cloud.height, /*rgbAsUnsigned=*/true) + "DATA ascii\n");
  const std::size_t points = std::size_t{cloud.width} * cloud.height;
  std::string text;
  text.reserve(kFlushBytes + 4096);
  const std::uint8_t* record = cloud.data.data();
  for (std::size_t i = 0; i < points; ++i, record += cloud.point_step) {
    bool first = true;
    for (const pcl::PCLPointField& field : fields) {
      // rgb is a float holding 4 bytes: as an unsigned integer, since opaque colours are NaNs.
      const std::uint8_t type = field.name == "rgb" && field.datatype == pcl::PCLPointField::FLOAT32
                                    ? std::uint8_t{pcl::PCLPointField::UINT32}
                                    : field.datatype;
      const int size = static_cast<int>(datatypeSize(type));
      for (std::uint32_t c = 0; c < countOf(field); ++c) {
        if (!first) text += ' ';
        first = false;
        appendFieldValue(text, type, record + field.offset + c * size, kAsciiPrecision);
      }
    }
    text += '\n';
    if (text.size() >= kFlushBytes) {
      out.write(text);
      text.clear();
    }
  }
  out.write(text);
}

void writeCompressedPcd(AtomicFile& out, const pcl::PCLPointCloud2& cloud) {
  const std::vector<pcl::PCLPointField> fields = realFields(cloud);
  const std::string header = pcdHeader(fields, cloud.width, cloud.height, /*rgbAsUnsigned=*/false);
  const std::size_t points = std::size_t{cloud.width} * cloud.height;
  std::size_t pointBytes = 0;
  for (const pcl::PCLPointField& field : fields) pointBytes += std::size_t{countOf(field)} * datatypeSize(field.datatype);
  const std::size_t dataSize = points * pointBytes;
  if (dataSize / 2 * 3 > std::numeric_limits<std::uint32_t>::max()) {
    throw std::runtime_error("the cloud's " + std::to_string(dataSize) +
                             " bytes are too many for a compressed PCD (at most 2.8 GB): write it binary");
  }
  std::uint32_t sizes[2] = {0, 0};  // compressed, uncompressed
  std::vector<std::uint8_t> compressed;
  if (dataSize > 0) {
    // Field-major: each field's values of every point together compress better.
    std::vector<std::uint8_t> planes(dataSize);
    std::uint8_t* to = planes.data();
    for (const pcl::PCLPointField& field : fields) {
      const std::size_t size = std::size_t{countOf(field)} * datatypeSize(field.datatype);
      const std::uint8_t* from = cloud.data.data() + field.offset;
      for (std::size_t i = 0; i < points; ++i, from += cloud.point_step, to += size) std::memcpy(to, from, size);
    }
    compressed.resize(dataSize / 2 * 3 + 16);
    const unsigned written = lzf_compress(planes.data(), static_cast<unsigned>(dataSize), compressed.data(),
                                          static_cast<unsigned>(compressed.size()));
    if (written == 0) throw std::runtime_error("LZF could not compress the cloud");
    compressed.resize(written);
    sizes[0] = written;
    sizes[1] = static_cast<std::uint32_t>(dataSize);
  }
  out.write(header + "DATA binary_compressed\n");
  out.write(sizes, sizeof(sizes));
  out.write(compressed.data(), compressed.size());
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
