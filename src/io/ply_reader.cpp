#include "ply_reader.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

#include <pcl/PCLPointField.h>

#include "cloud_read_error.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

enum class Encoding { Ascii, LittleEndian, BigEndian };

struct Property {
  std::string name;
  std::uint8_t type = 0;       ///< pcl::PCLPointField datatype of the value (or of a list's items)
  std::uint8_t countType = 0;  ///< a list's count type; 0 for a scalar
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;
  std::vector<Property> properties;
};

std::uint8_t plyType(std::string_view name) {
  if (name == "char" || name == "int8") return pcl::PCLPointField::INT8;
  if (name == "uchar" || name == "uint8") return pcl::PCLPointField::UINT8;
  if (name == "short" || name == "int16") return pcl::PCLPointField::INT16;
  if (name == "ushort" || name == "uint16") return pcl::PCLPointField::UINT16;
  if (name == "int" || name == "int32") return pcl::PCLPointField::INT32;
  if (name == "uint" || name == "uint32") return pcl::PCLPointField::UINT32;
  if (name == "float" || name == "float32") return pcl::PCLPointField::FLOAT32;
  if (name == "double" || name == "float64") return pcl::PCLPointField::FLOAT64;
  return 0;
}

bool isIntegerType(std::uint8_t type) {
  return type != 0 && type != pcl::PCLPointField::FLOAT32 && type != pcl::PCLPointField::FLOAT64;
}

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::uint64_t cols = 0;
  std::uint64_t rows = 0;
  std::size_t bodyStart = 0;
  int bodyLine = 0;  ///< the end_header line's number
};

Header readHeader(const std::string& source, const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Header header;
  std::size_t position = 0;
  bool haveFormat = false;
  for (int number = 1; position < text.size(); ++number) {
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(position, end - position);
    position = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string where = "header line " + std::to_string(number) + ": ";
    if (number == 1) {
      if (line != "ply") failCloudRead(source, "not a PLY file (it does not start with 'ply')");
      continue;
    }
    const std::vector<std::string_view> tokens = splitWhitespace(line);
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "comment") continue;
    if (key == "obj_info") {
      // PCL records an organized cloud's layout here.
      std::uint64_t value = 0;
      if (tokens.size() == 3 && (tokens[1] == "num_cols" || tokens[1] == "num_rows")) {
        if (!parseCount(tokens[2], UINT32_MAX, value)) failCloudRead(source, where + "obj_info value is not a count");
        (tokens[1] == "num_cols" ? header.cols : header.rows) = value;
      }
      continue;
    }
    if (key == "format") {
      if (haveFormat || tokens.size() != 3 || tokens[2] != "1.0") failCloudRead(source, where + "expected one 'format <encoding> 1.0'");
      haveFormat = true;
      if (tokens[1] == "ascii") header.encoding = Encoding::Ascii;
      else if (tokens[1] == "binary_little_endian") header.encoding = Encoding::LittleEndian;
      else if (tokens[1] == "binary_big_endian") header.encoding = Encoding::BigEndian;
      else failCloudRead(source, where + "unknown format '" + std::string(tokens[1].substr(0, 40)) + "'");
      continue;
    }
    if (key == "element") {
      Element element;
      element.line = number;
      if (tokens.size() != 3 || !parseCount(tokens[2], UINT64_MAX, element.count)) {
        failCloudRead(source, where + "expected 'element <name> <count>' with a count of 0 or more");
      }
      element.name = std::string(tokens[1].substr(0, 40));
      for (const Element& earlier : header.elements) {
        if (earlier.name == element.name) failCloudRead(source, where + "element '" + element.name + "' appears twice");
      }
      header.elements.push_back(element);
      continue;
    }
    if (key == "property") {
      if (header.elements.empty()) failCloudRead(source, where + "a property before any element");
      Property property;
      const bool isList = tokens.size() == 5 && tokens[1] == "list";
      if (!isList && tokens.size() != 3) failCloudRead(source, where + "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
      property.name = std::string(tokens.back().substr(0, 40));
      property.type = plyType(tokens[isList ? 3 : 1]);
      if (isList) property.countType = plyType(tokens[2]);
      if (property.type == 0 || (isList && !isIntegerType(property.countType))) {
        failCloudRead(source, where + "property '" + property.name + "' has an unknown type");
      }
      for (const Property& earlier : header.elements.back().properties) {
        if (earlier.name == property.name) failCloudRead(source, where + "property '" + property.name + "' appears twice");
      }
      header.elements.back().properties.push_back(property);
      continue;
    }
    if (key == "end_header" && tokens.size() == 1) {
      if (!haveFormat) failCloudRead(source, "the header has no 'format' line");
      header.bodyStart = std::min(position, text.size());
      header.bodyLine = number;
      return header;
    }
    failCloudRead(source, where + "unknown header line '" + std::string(line.substr(0, 40)) + "'");
  }
  failCloudRead(source, "the header has no end_header line: truncated?");
}

/// Reads the body value by value, from ASCII lines or binary bytes, in bounds.
class BodyReader {
 public:
  BodyReader(const std::string& source, const Header& header, const std::uint8_t* data, std::size_t size)
      : source_(source), encoding_(header.encoding), data_(data + header.bodyStart), size_(size - header.bodyStart),
        line_(header.bodyLine) {}

  std::uint64_t remaining() const { return size_ - position_; }

  /// Starts the next element entry: an ASCII line (skipping blank ones).
  void beginEntry() {
    if (encoding_ != Encoding::Ascii) return;
    tokens_.clear();
    token_ = 0;
    const std::string_view text(reinterpret_cast<const char*>(data_), size_);
    while (tokens_.empty()) {
      if (position_ >= text.size()) failCloudRead(source_, "the data ends before the header's entries: truncated?");
      std::size_t end = text.find('\n', position_);
      if (end == std::string_view::npos) end = text.size();
      tokens_ = splitWhitespace(text.substr(position_, end - position_));
      position_ = end + 1 > text.size() ? text.size() : end + 1;
      ++line_;
    }
  }

  /// Ends an entry: an ASCII line must hold nothing more.
  void endEntry() {
    if (encoding_ == Encoding::Ascii && token_ != tokens_.size()) {
      failCloudRead(source_, "line " + std::to_string(line_) + ": " + std::to_string(tokens_.size()) +
                                 " values, more than the header's properties: malformed?");
    }
  }

  /// One value of `type`, stored in host order at `destination`.
  void value(std::uint8_t type, const std::string& name, std::uint8_t* destination) {
    const std::size_t bytes = datatypeSize(type);
    if (encoding_ == Encoding::Ascii) {
      if (token_ >= tokens_.size()) {
        failCloudRead(source_, "line " + std::to_string(line_) + ": too few values (property '" + name + "' missing)");
      }
      if (!parseValue(tokens_[token_], type, destination)) {
        failCloudRead(source_, "line " + std::to_string(line_) + ": value '" + std::string(tokens_[token_].substr(0, 40)) +
                                   "' of property '" + name + "' is not a " + datatypeName(type));
      }
      ++token_;
      return;
    }
    if (bytes > remaining()) failCloudRead(source_, "the data ends inside property '" + name + "': truncated?");
    std::memcpy(destination, data_ + position_, bytes);
    if (encoding_ == Encoding::BigEndian) std::reverse(destination, destination + bytes);  // hosts are little-endian
    position_ += bytes;
  }

  /// An integer value of `type` (a list count or index) as int64.
  std::int64_t integer(std::uint8_t type, const std::string& name) {
    std::uint8_t bytes[8] = {};
    value(type, name, bytes);
    switch (type) {
      case pcl::PCLPointField::INT8: { std::int8_t v; std::memcpy(&v, bytes, 1); return v; }
      case pcl::PCLPointField::UINT8: return bytes[0];
      case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy(&v, bytes, 2); return v; }
      case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy(&v, bytes, 2); return v; }
      case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy(&v, bytes, 4); return v; }
      case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy(&v, bytes, 4); return v; }
      default: failCloudRead(source_, "property '" + name + "' must be an integer");
    }
  }

  int line() const { return line_; }

 private:
  std::string source_;
  Encoding encoding_;
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  int line_;
  std::vector<std::string_view> tokens_;
  std::size_t token_ = 0;
};

// Every entry takes at least its smallest encoding: a byte per binary value, or a character and
// a separator per ASCII value. Checked before anything of `count` entries is allocated.
void requireRoom(const std::string& source, const Element& element, std::uint64_t bytesPerEntry, Encoding encoding,
                 std::uint64_t available) {
  // An entry without properties takes no bytes at all: counted as one, so that its count stays
  // bounded by the file too (2^64 - 1 of them would loop for ever).
  const std::uint64_t perEntry =
      std::max<std::uint64_t>(1, encoding == Encoding::Ascii ? 2 * element.properties.size() : bytesPerEntry);
  if (saturatingMultiply(element.count, perEntry) > available + 1) {
    failCloudRead(source, "element '" + element.name + "' declares " + std::to_string(element.count) +
                              " entries but the data holds only " + std::to_string(available) + " bytes: truncated?");
  }
}

void readVertices(const std::string& source, const Header& header, const Element& vertex, BodyReader& body,
                  std::uint64_t maxPoints, pcl::PCLPointCloud2& blob) {
  if (vertex.count > maxPoints) {
    failCloudRead(source, std::to_string(vertex.count) + " vertices is more than the limit of " +
                              std::to_string(maxPoints) + " points per scan");
  }
  std::uint32_t offset = 0;
  for (const Property& property : vertex.properties) {
    if (property.countType != 0) {
      failCloudRead(source, "header line " + std::to_string(vertex.line) + ": list property '" + property.name +
                                "' in element vertex is not supported");
    }
    pcl::PCLPointField field;
    field.name = property.name;
    field.datatype = property.type;
    field.count = 1;
    field.offset = offset;
    offset += static_cast<std::uint32_t>(datatypeSize(property.type));
    blob.fields.push_back(field);
  }
  blob.point_step = offset;
  requireRoom(source, vertex, offset, header.encoding, body.remaining());
  blob.width = static_cast<std::uint32_t>(vertex.count);
  blob.height = 1;
  blob.row_step = static_cast<std::uint32_t>(std::min<std::uint64_t>(UINT32_MAX, std::uint64_t{offset} * vertex.count));
  blob.data.resize(static_cast<std::size_t>(vertex.count * offset));
  for (std::uint64_t i = 0; i < vertex.count; ++i) {
    body.beginEntry();
    std::uint8_t* record = blob.data.data() + i * offset;
    for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
      body.value(vertex.properties[p].type, vertex.properties[p].name, record + blob.fields[p].offset);
    }
    body.endEntry();
  }
}

// PCL's layout of an organized cloud: one cell per pixel listing 0 or 1 vertex indices.
void readGrid(const std::string& source, const Header& header, const Element& grid, std::uint64_t vertices,
              BodyReader& body, PlyContent& content) {
  if (grid.properties.size() != 1 || grid.properties[0].countType == 0 || !isIntegerType(grid.properties[0].type)) {
    failCloudRead(source, "header line " + std::to_string(grid.line) + ": range_grid must have one integer list property");
  }
  if (grid.count != header.cols * header.rows) {
    failCloudRead(source, "range_grid has " + std::to_string(grid.count) + " cells but obj_info num_cols x num_rows is " +
                              std::to_string(header.cols) + " x " + std::to_string(header.rows));
  }
  const Property& list = grid.properties[0];
  requireRoom(source, grid, datatypeSize(list.countType), header.encoding, body.remaining());
  content.grid.resize(static_cast<std::size_t>(grid.count));
  for (std::int64_t& cell : content.grid) {
    body.beginEntry();
    const std::int64_t n = body.integer(list.countType, list.name);
    if (n != 0 && n != 1) failCloudRead(source, "a range_grid cell lists " + std::to_string(n) + " vertices (0 or 1 expected)");
    cell = n == 0 ? -1 : body.integer(list.type, list.name);
    if (n == 1 && (cell < 0 || static_cast<std::uint64_t>(cell) >= vertices)) {
      failCloudRead(source, "a range_grid cell names vertex " + std::to_string(cell) + " of " + std::to_string(vertices));
    }
    body.endEntry();
  }
  content.gridWidth = static_cast<std::uint32_t>(header.cols);
  content.gridHeight = static_cast<std::uint32_t>(header.rows);
}

// An element that is not read is still walked through, in bounds: a file cut anywhere is refused.
void skipElement(const std::string& source, const Header& header, const Element& element, BodyReader& body) {
  std::uint64_t minimumBytes = 0;
  for (const Property& property : element.properties) {
    minimumBytes += datatypeSize(property.countType != 0 ? property.countType : property.type);
  }
  requireRoom(source, element, minimumBytes, header.encoding, body.remaining());
  std::uint8_t scratch[8];
  for (std::uint64_t i = 0; i < element.count; ++i) {
    body.beginEntry();
    for (const Property& property : element.properties) {
      std::int64_t n = 1;
      if (property.countType != 0) {
        n = body.integer(property.countType, property.name);
        if (n < 0) failCloudRead(source, "a list of element '" + element.name + "' has a negative count");
      }
      for (std::int64_t k = 0; k < n; ++k) body.value(property.type, property.name, scratch);
    }
    body.endEntry();
  }
}

// PCL's other layout record (use_camera): a camera element whose viewportx x viewporty is the
// organized cloud's width x height, the vertices then being all of its points in row order.
void readCamera(const std::string& source, const Header& header, const Element& camera, std::uint64_t vertices,
                BodyReader& body, PlyContent& content) {
  if (camera.count != 1) return skipElement(source, header, camera, body);
  for (const Property& property : camera.properties) {
    if (property.countType != 0) return skipElement(source, header, camera, body);
  }
  std::int64_t width = -1;
  std::int64_t height = -1;
  std::uint8_t scratch[8];
  body.beginEntry();
  for (const Property& property : camera.properties) {
    const bool isViewport = property.name == "viewportx" || property.name == "viewporty";
    if (!isViewport || !isIntegerType(property.type)) {
      body.value(property.type, property.name, scratch);
      continue;
    }
    (property.name == "viewportx" ? width : height) = body.integer(property.type, property.name);
  }
  body.endEntry();
  if (width > 0 && height > 0 && static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) == vertices &&
      content.grid.empty()) {
    content.blob.width = static_cast<std::uint32_t>(width);
    content.blob.height = static_cast<std::uint32_t>(height);
    content.blob.row_step = content.blob.point_step * content.blob.width;
  }
}

}  // namespace

PlyContent parsePly(const std::string& source, const std::uint8_t* data, std::size_t size, std::uint64_t maxPoints) {
  const Header header = readHeader(source, data, size);
  if (header.elements.empty() || header.elements[0].name != "vertex") {
    failCloudRead(source, "the first element must be 'vertex'");
  }
  PlyContent content;
  BodyReader body(source, header, data, size);
  const Element& vertex = header.elements[0];
  readVertices(source, header, vertex, body, maxPoints, content.blob);
  // Elements after the vertices are ignored, but for the range_grid that keeps the layout.
  for (std::size_t e = 1; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    if (element.name == "range_grid") {
      readGrid(source, header, element, vertex.count, body, content);
    } else if (element.name == "camera") {
      readCamera(source, header, element, vertex.count, body, content);
    } else {
      skipElement(source, header, element, body);
    }
  }
  return content;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
