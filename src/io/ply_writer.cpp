#include "ply_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "field_text.hpp"
#include "text_values.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

const char* plyType(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: return "char";
    case pcl::PCLPointField::UINT8: return "uchar";
    case pcl::PCLPointField::INT16: return "short";
    case pcl::PCLPointField::UINT16: return "ushort";
    case pcl::PCLPointField::INT32: return "int";
    case pcl::PCLPointField::UINT32: return "uint";
    case pcl::PCLPointField::FLOAT32: return "float";
    case pcl::PCLPointField::FLOAT64: return "double";
    default: return nullptr;
  }
}

/// How a field is written: as its values, or as the colour bytes red green blue [alpha] of
/// PCL's packed rgb (float) / rgba (uint32), stored b g r a.
enum class Kind { Values, Rgb, Rgba };

struct Field {
  pcl::PCLPointField field;
  Kind kind = Kind::Values;
  std::uint32_t count = 1;
  int size = 0;
};

std::vector<Field> plyFields(const pcl::PCLPointCloud2& cloud) {
  std::vector<Field> fields;
  for (const pcl::PCLPointField& field : cloud.fields) {
    if (field.name == "_") continue;  // PCL's name for padding
    Field f;
    f.field = field;
    f.count = std::max<std::uint32_t>(field.count, 1);
    f.size = static_cast<int>(datatypeSize(field.datatype));
    if (plyType(field.datatype) == nullptr) {
      throw std::runtime_error("field '" + field.name + "' has a type PLY cannot hold (" +
                               std::to_string(field.datatype) + ")");
    }
    if (field.name == "rgb" || field.name == "rgba") {
      if (f.size != 4 || f.count != 1) throw std::runtime_error("field '" + field.name + "' is not 4 bytes of colour");
      f.kind = field.name == "rgb" ? Kind::Rgb : Kind::Rgba;
    }
    fields.push_back(f);
  }
  return fields;
}

std::string header(const pcl::PCLPointCloud2& cloud, const std::vector<Field>& fields, bool binary,
                   std::uint64_t vertices) {
  std::string h = binary ? "ply\nformat binary_little_endian 1.0" : "ply\nformat ascii 1.0";
  // PCL's header: the obj_info block is how its readers (and ours) learn an organized cloud's
  // width and height.
  h += "\ncomment PCL generated\nobj_info is_cyberware_data 0\nobj_info is_mesh 0\nobj_info is_warped 0"
       "\nobj_info is_interlaced 0\nobj_info num_cols " +
       std::to_string(cloud.width) + "\nobj_info num_rows " + std::to_string(cloud.height) +
       "\nobj_info echo_rgb_offset_x 0\nobj_info echo_rgb_offset_y 0\nobj_info echo_rgb_offset_z 0"
       "\nobj_info echo_rgb_frontfocus 0.0\nobj_info echo_rgb_backfocus 0.0\nobj_info echo_rgb_pixelsize 0.0"
       "\nobj_info echo_rgb_centerpixel 0\nobj_info echo_frames 1\nobj_info echo_lgincr 0.0";
  h += "\nelement vertex " + std::to_string(vertices);
  for (const Field& f : fields) {
    const std::string& name = f.field.name;
    if (f.kind == Kind::Rgb) {
      h += "\nproperty uchar red\nproperty uchar green\nproperty uchar blue";
    } else if (f.kind == Kind::Rgba) {
      h += "\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha";
    } else if ((name == "normal_x" || name == "normal_y" || name == "normal_z") &&
               f.field.datatype == pcl::PCLPointField::FLOAT32 && f.field.count == 1) {
      h += std::string("\nproperty float n") + name.back();
    } else {
      h += "\nproperty";
      if (f.field.count != 1) h += " list uint";
      h += std::string(" ") + plyType(f.field.datatype) + " " + name;
    }
  }
  h += "\nelement face 0";  // VTK's reader needs a face element
  if (cloud.height > 1) {
    h += "\nelement range_grid " + std::to_string(std::uint64_t{cloud.width} * cloud.height) +
         "\nproperty list uchar int vertex_indices";
  }
  return h + "\nend_header\n";
}

/// Whether point i's x is finite (points without a float x are all valid).
std::vector<bool> validPoints(const pcl::PCLPointCloud2& cloud, std::size_t points) {
  std::vector<bool> valid(points, true);
  for (const pcl::PCLPointField& field : cloud.fields) {
    if (field.name != "x" || field.datatype != pcl::PCLPointField::FLOAT32) continue;
    for (std::size_t i = 0; i < points; ++i) {
      float x;
      std::memcpy(&x, cloud.data.data() + i * cloud.point_step + field.offset, sizeof(x));
      valid[i] = std::isfinite(x);
    }
    break;
  }
  return valid;
}

void appendColour(std::string& text, const std::uint8_t* bgra, bool alpha) {
  text += std::to_string(bgra[2]) + ' ' + std::to_string(bgra[1]) + ' ' + std::to_string(bgra[0]);
  if (alpha) text += ' ' + std::to_string(bgra[3]);
}

void appendAsciiPoint(std::string& text, const std::vector<Field>& fields, const std::uint8_t* record) {
  bool first = true;
  for (const Field& f : fields) {
    if (!first) text += ' ';
    first = false;
    if (f.field.count > 1) text += std::to_string(f.count) + ' ';
    for (std::uint32_t c = 0; c < f.count; ++c) {
      if (c > 0) text += ' ';
      const std::uint8_t* value = record + f.field.offset + c * f.size;
      if (f.kind == Kind::Values) {
        appendFieldValue(text, f.field.datatype, value, kAsciiPrecision);
      } else {
        appendColour(text, value, f.kind == Kind::Rgba);
      }
    }
  }
  text += '\n';
}

void appendBinaryPoint(std::string& bytes, const std::vector<Field>& fields, const std::uint8_t* record) {
  for (const Field& f : fields) {
    if (f.field.count > 1) bytes.append(reinterpret_cast<const char*>(&f.count), sizeof(f.count));
    for (std::uint32_t c = 0; c < f.count; ++c) {
      const std::uint8_t* value = record + f.field.offset + c * f.size;
      if (f.kind == Kind::Values) {
        bytes.append(reinterpret_cast<const char*>(value), static_cast<std::size_t>(f.size));
      } else {
        const char colour[4] = {static_cast<char>(value[2]), static_cast<char>(value[1]), static_cast<char>(value[0]),
                                static_cast<char>(value[3])};
        bytes.append(colour, f.kind == Kind::Rgba ? 4 : 3);
      }
    }
  }
}

}  // namespace

void writePly(AtomicFile& out, const pcl::PCLPointCloud2& cloud, bool binary) {
  const std::vector<Field> fields = plyFields(cloud);
  const std::size_t points = std::size_t{cloud.width} * cloud.height;
  const bool organized = cloud.height > 1;
  // PCL leaves out the points without a finite x in ASCII, and in binary where a range_grid can
  // say so (organized clouds).
  const bool dropInvalid = !binary || organized;
  std::vector<bool> valid = validPoints(cloud, points);
  if (!dropInvalid) valid.assign(points, true);
  const std::uint64_t vertices = static_cast<std::uint64_t>(std::count(valid.begin(), valid.end(), true));
  out.write(header(cloud, fields, binary, vertices));

  std::string body;
  body.reserve(kFlushBytes + 4096);
  const auto flush = [&](bool always) {
    if (always || body.size() >= kFlushBytes) {
      out.write(body);
      body.clear();
    }
  };
  const std::uint8_t* record = cloud.data.data();
  for (std::size_t i = 0; i < points; ++i, record += cloud.point_step) {
    if (!valid[i]) continue;
    if (binary) {
      appendBinaryPoint(body, fields, record);
    } else {
      appendAsciiPoint(body, fields, record);
    }
    flush(false);
  }
  if (organized) {
    // range_grid: per pixel, the list of its vertex (one or none).
    std::int32_t next = 0;
    for (std::size_t i = 0; i < points; ++i) {
      if (binary) {
        const char length = valid[i] ? 1 : 0;
        body += length;
        if (valid[i]) body.append(reinterpret_cast<const char*>(&next), sizeof(next));
      } else {
        body += valid[i] ? "1 " + std::to_string(next) + "\n" : std::string("0\n");
      }
      if (valid[i]) ++next;
      flush(false);
    }
  }
  flush(true);
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
