#include "pcd_reader.hpp"

#include <cmath>
#include <cstring>
#include <map>
#include <string_view>
#include <vector>

#include <pcl/PCLPointField.h>

#include "cloud_read_error.hpp"
#include "lzf_decoder.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

// Bounds that no real file comes near and that keep every product below 2^64: a field of
// COUNT values (FPFH: 33, VFH: 308), a name list of FIELDS.
constexpr std::uint64_t kMaxFieldCount = 1u << 20;
constexpr std::uint64_t kMaxDimension = UINT32_MAX;

/// The header's lines by key, each kept with its line number for messages.
struct HeaderLine {
  int number = 0;
  std::vector<std::string_view> values;
};

class PcdHeader {
 public:
  PcdHeader(const std::string& source, const std::uint8_t* data, std::size_t size) : source_(source) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::size_t position = 0;
    for (int number = 1; position < text.size(); ++number) {
      std::size_t end = text.find('\n', position);
      if (end == std::string_view::npos) end = text.size();
      const std::string_view line = text.substr(position, end - position);
      position = end + 1;
      const std::vector<std::string_view> tokens = splitWhitespace(line);
      if (tokens.empty() || tokens[0][0] == '#') continue;
      const std::string key(tokens[0]);
      static const char* const known[] = {"VERSION", "FIELDS", "SIZE", "TYPE", "COUNT", "WIDTH",
                                          "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
      bool isKnown = false;
      for (const char* k : known) isKnown = isKnown || key == k;
      if (!isKnown) {
        fail(number, "not a PCD file: unknown header key '" + std::string(tokens[0].substr(0, 40)) + "'");
      }
      if (lines_.count(key) != 0) {
        fail(number, "'" + key + "' appears again (first on line " + std::to_string(lines_[key].number) + ")");
      }
      lines_[key] = HeaderLine{number, {tokens.begin() + 1, tokens.end()}};
      if (key == "DATA") {
        dataStart_ = position > text.size() ? text.size() : position;
        return;
      }
    }
    failRead(lines_.count("FIELDS") == 0 ? "not a PCD file (no FIELDS in its header)"
                                         : "the header has no DATA line: truncated?");
  }

  std::size_t dataStart() const { return dataStart_; }
  bool has(const std::string& key) const { return lines_.count(key) != 0; }

  const HeaderLine& line(const std::string& key) const {
    const auto found = lines_.find(key);
    if (found == lines_.end()) failRead("the header has no " + key + " line");
    return found->second;
  }

  /// The values of `key`, exactly `count` of them (any number >= 1 when count is 0).
  const HeaderLine& values(const std::string& key, std::size_t count) const {
    const HeaderLine& found = line(key);
    if (count == 0 ? found.values.empty() : found.values.size() != count) {
      fail(found.number, key + " has " + std::to_string(found.values.size()) + " values, expected " +
                             (count == 0 ? std::string("at least 1") : std::to_string(count)));
    }
    return found;
  }

  std::uint64_t count(const std::string& key, std::size_t index, std::uint64_t max) const {
    const HeaderLine& found = line(key);
    std::uint64_t value = 0;
    if (!parseCount(found.values[index], max, value)) {
      fail(found.number, key + " value '" + std::string(found.values[index].substr(0, 40)) +
                             "' is not a whole number from 0 to " + std::to_string(max));
    }
    return value;
  }

  [[noreturn]] void fail(int number, const std::string& problem) const {
    failRead("header line " + std::to_string(number) + ": " + problem);
  }
  [[noreturn]] void failRead(const std::string& problem) const { failCloudRead(source_, problem); }

 private:
  std::string source_;
  std::map<std::string, HeaderLine> lines_;
  std::size_t dataStart_ = 0;
};

std::uint8_t datatypeOf(const PcdHeader& header, char type, std::uint64_t size, int line, const std::string& field) {
  if (type == 'F' && (size == 4 || size == 8)) return size == 4 ? pcl::PCLPointField::FLOAT32 : pcl::PCLPointField::FLOAT64;
  if (type == 'I' || type == 'U') {
    const bool isSigned = type == 'I';
    switch (size) {
      case 1: return isSigned ? pcl::PCLPointField::INT8 : pcl::PCLPointField::UINT8;
      case 2: return isSigned ? pcl::PCLPointField::INT16 : pcl::PCLPointField::UINT16;
      case 4: return isSigned ? pcl::PCLPointField::INT32 : pcl::PCLPointField::UINT32;
      case 8: return isSigned ? pcl::PCLPointField::INT64 : pcl::PCLPointField::UINT64;
      default: break;
    }
  }
  header.fail(line, "field '" + field + "' has TYPE '" + std::string(1, type) + "' with SIZE " + std::to_string(size) +
                        " (accepted: I or U of 1, 2, 4, 8 bytes; F of 4 or 8)");
}

/// FIELDS, SIZE, TYPE and COUNT into PCL's packed fields; returns the point record's size.
std::uint64_t readFields(const PcdHeader& header, pcl::PCLPointCloud2& blob) {
  const HeaderLine& names = header.values("FIELDS", 0);
  const std::size_t n = names.values.size();
  const HeaderLine& types = header.values("TYPE", n);
  header.values("SIZE", n);
  if (header.has("COUNT")) header.values("COUNT", n);
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < n; ++i) {
    pcl::PCLPointField field;
    field.name = std::string(names.values[i]);
    for (const pcl::PCLPointField& earlier : blob.fields) {
      if (earlier.name == field.name && field.name != "_") {  // "_" is PCL's padding, repeated
        header.fail(names.number, "field '" + field.name + "' appears twice");
      }
    }
    const std::uint64_t size = header.count("SIZE", i, 8);
    const std::uint64_t count = header.has("COUNT") ? header.count("COUNT", i, kMaxFieldCount) : 1;
    if (count == 0) header.fail(header.line("COUNT").number, "field '" + field.name + "' has COUNT 0");
    if (types.values[i].size() != 1) {
      header.fail(types.number, "field '" + field.name + "' has TYPE '" + std::string(types.values[i].substr(0, 8)) + "'");
    }
    field.datatype = datatypeOf(header, types.values[i][0], size, types.number, field.name);
    field.count = static_cast<std::uint32_t>(count);
    field.offset = static_cast<std::uint32_t>(offset);
    offset += size * count;  // <= 2^20 fields' worth of 8 x 2^20 bytes: no wrap
    if (offset > UINT32_MAX) header.fail(names.number, "the point record is over 4 GB");
    blob.fields.push_back(field);
  }
  return offset;
}

void readViewpoint(const PcdHeader& header, PcdContent& content) {
  if (!header.has("VIEWPOINT")) return;
  const HeaderLine& line = header.values("VIEWPOINT", 7);
  double v[7];
  for (int i = 0; i < 7; ++i) {
    if (!parseReal(line.values[static_cast<std::size_t>(i)], v[i]) || !std::isfinite(v[i]) || std::fabs(v[i]) > 1e30) {
      header.fail(line.number, "VIEWPOINT value '" + std::string(line.values[static_cast<std::size_t>(i)].substr(0, 40)) +
                                   "' is not a finite number");
    }
  }
  content.origin = Eigen::Vector4f(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), 0.0f);
  content.orientation = Eigen::Quaternionf(static_cast<float>(v[3]), static_cast<float>(v[4]), static_cast<float>(v[5]),
                                           static_cast<float>(v[6]));
}

[[noreturn]] void failShort(const std::string& source, std::uint64_t available, const pcl::PCLPointCloud2& blob) {
  failCloudRead(source, "the data holds " + std::to_string(available) + " bytes but the header declares " +
                            std::to_string(blob.width) + " x " + std::to_string(blob.height) + " points of " +
                            std::to_string(blob.point_step) + " bytes: truncated?");
}

std::uint32_t littleEndian32(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24);
}

// binary_compressed: uint32 compressed size, uint32 uncompressed size, an LZF block holding each
// field's values for all points in turn (structure of arrays), turned back into point records.
void readCompressed(const std::string& source, const std::uint8_t* body, std::uint64_t available, std::uint64_t bytes,
                    pcl::PCLPointCloud2& blob) {
  if (available < 8) failShort(source, available, blob);
  const std::uint64_t compressedSize = littleEndian32(body);
  const std::uint64_t uncompressedSize = littleEndian32(body + 4);
  if (compressedSize > available - 8) {
    failCloudRead(source, "the compressed block declares " + std::to_string(compressedSize) + " bytes but " +
                              std::to_string(available - 8) + " follow: truncated?");
  }
  if (uncompressedSize != bytes) {
    failCloudRead(source, "the compressed block declares " + std::to_string(uncompressedSize) +
                              " uncompressed bytes but the header's points need " + std::to_string(bytes));
  }
  if (bytes == 0) return;
  if (bytes > compressedSize * kLzfMaxExpansion) {
    failCloudRead(source, "the compressed block of " + std::to_string(compressedSize) + " bytes cannot hold " +
                              std::to_string(bytes) + " bytes (LZF expands at most " +
                              std::to_string(kLzfMaxExpansion) + "x): corrupted?");
  }
  std::vector<std::uint8_t> columns(static_cast<std::size_t>(bytes));
  if (!lzfDecode(body + 8, static_cast<std::size_t>(compressedSize), columns.data(), columns.size())) {
    failCloudRead(source, "the compressed block is corrupted (LZF data does not decode to " + std::to_string(bytes) +
                              " bytes)");
  }
  const std::size_t points = static_cast<std::size_t>(blob.width) * blob.height;
  blob.data.resize(static_cast<std::size_t>(bytes));
  std::size_t column = 0;
  for (const pcl::PCLPointField& field : blob.fields) {
    const std::size_t fieldBytes = datatypeSize(field.datatype) * field.count;
    for (std::size_t i = 0; i < points; ++i) {
      std::memcpy(&blob.data[i * blob.point_step + field.offset], &columns[column + i * fieldBytes], fieldBytes);
    }
    column += points * fieldBytes;
  }
}

// One line per point, one token per value; a value that does not parse names its line.
void readAscii(const std::string& source, const std::uint8_t* body, std::uint64_t available, std::size_t lineOffset,
               pcl::PCLPointCloud2& blob) {
  std::uint64_t valuesPerPoint = 0;
  for (const pcl::PCLPointField& field : blob.fields) valuesPerPoint += field.count;
  const std::uint64_t points = static_cast<std::uint64_t>(blob.width) * blob.height;
  // Every value takes a character and a separator: checked before the points are allocated.
  if (saturatingMultiply(points, valuesPerPoint) > available / 2 + 1) {
    failCloudRead(source, "the data holds " + std::to_string(available) + " bytes, too few for the header's " +
                              std::to_string(points) + " points of " + std::to_string(valuesPerPoint) +
                              " values: truncated?");
  }
  blob.data.resize(static_cast<std::size_t>(points * blob.point_step));
  const std::string_view text(reinterpret_cast<const char*>(body), static_cast<std::size_t>(available));
  std::uint64_t point = 0;
  std::size_t position = 0;
  for (std::size_t number = lineOffset + 1; position < text.size(); ++number) {
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos) end = text.size();
    const std::vector<std::string_view> tokens = splitWhitespace(text.substr(position, end - position));
    position = end + 1;
    if (tokens.empty()) continue;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (point == points) failCloudRead(source, where + "more points than the header's POINTS " + std::to_string(points));
    if (tokens.size() != valuesPerPoint) {
      failCloudRead(source, where + std::to_string(tokens.size()) + " values, expected " +
                                std::to_string(valuesPerPoint) + ": truncated or malformed?");
    }
    std::size_t token = 0;
    std::uint8_t* record = blob.data.data() + point * blob.point_step;
    for (const pcl::PCLPointField& field : blob.fields) {
      const std::size_t valueBytes = datatypeSize(field.datatype);
      for (std::uint32_t k = 0; k < field.count; ++k, ++token) {
        if (!parseValue(tokens[token], field.datatype, record + field.offset + k * valueBytes)) {
          failCloudRead(source, where + "value '" + std::string(tokens[token].substr(0, 40)) + "' of field '" +
                                    field.name + "' is not a " + datatypeName(field.datatype));
        }
      }
    }
    ++point;
  }
  if (point < points) {
    failCloudRead(source, "the header declares " + std::to_string(points) + " points but the data holds " +
                              std::to_string(point) + ": truncated?");
  }
}

}  // namespace

PcdContent parsePcd(const std::string& source, const std::uint8_t* data, std::size_t size, std::uint64_t maxPoints) {
  const PcdHeader header(source, data, size);
  PcdContent content;
  pcl::PCLPointCloud2& blob = content.blob;
  blob.point_step = static_cast<std::uint32_t>(readFields(header, blob));
  header.values("WIDTH", 1);
  header.values("HEIGHT", 1);
  header.values("POINTS", 1);
  blob.width = static_cast<std::uint32_t>(header.count("WIDTH", 0, kMaxDimension));
  blob.height = static_cast<std::uint32_t>(header.count("HEIGHT", 0, kMaxDimension));
  const std::uint64_t points = header.count("POINTS", 0, UINT64_MAX);
  if (points != static_cast<std::uint64_t>(blob.width) * blob.height) {
    header.fail(header.line("POINTS").number, "POINTS " + std::to_string(points) + " is not WIDTH x HEIGHT = " +
                                                  std::to_string(blob.width) + " x " + std::to_string(blob.height));
  }
  if (points > maxPoints) {
    failCloudRead(source, std::to_string(points) + " points is more than the limit of " + std::to_string(maxPoints) +
                              " points per scan");
  }
  const std::uint64_t rowStep = static_cast<std::uint64_t>(blob.point_step) * blob.width;
  blob.row_step = rowStep <= UINT32_MAX ? static_cast<std::uint32_t>(rowStep) : 0;  // 0: packed rows
  readViewpoint(header, content);

  const HeaderLine& dataLine = header.values("DATA", 1);
  const std::string encoding(dataLine.values[0]);
  const std::uint64_t available = size - header.dataStart();
  const std::uint8_t* body = data + header.dataStart();
  const std::uint64_t bytes = saturatingMultiply(points, blob.point_step);
  if (encoding == "ascii") {
    readAscii(source, body, available, static_cast<std::size_t>(dataLine.number), blob);
  } else if (encoding == "binary") {
    if (bytes > available) failShort(source, available, blob);
    blob.data.assign(body, body + bytes);
  } else if (encoding == "binary_compressed") {
    readCompressed(source, body, available, bytes, blob);
  } else {
    header.fail(dataLine.number, "DATA '" + encoding.substr(0, 40) + "' (accepted: ascii, binary, binary_compressed)");
  }
  return content;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
