#include "binary_pcd_writer.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "field_text.hpp"
#include "text_values.hpp"
#include "pcd_writer.hpp"

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

/// Bytes copied from each point record: fields that touch in the record form one span
/// (PointXYZRGB: x y z, then rgb), so a point costs a couple of small copies.
struct Span {
  std::size_t from = 0;
  std::size_t size = 0;
};

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

[[noreturn]] void fail(const std::string& problem) { throw std::runtime_error(problem); }

}  // namespace

void writeBinaryPcd(AtomicFile& out, const pcl::PCLPointCloud2& layout, const std::uint8_t* records) {
  // The header declares exactly the fields and sizes of the packed records.
  std::vector<pcl::PCLPointField> packed;
  std::vector<Span> spans;
  std::size_t step = 0;
  for (const pcl::PCLPointField& field : layout.fields) {
    if (field.name == "_") continue;  // PCL's name for padding
    pcl::PCLPointField packedField = field;
    packedField.count = std::max<std::uint32_t>(field.count, 1);
    packedField.offset = static_cast<std::uint32_t>(step);
    const std::size_t size = datatypeSize(field.datatype) * packedField.count;
    if (size == 0) fail("field '" + field.name + "' has an unsupported type (" + std::to_string(field.datatype) + ")");
    if (field.offset + size > layout.point_step) {
      fail("field '" + field.name + "' lies outside the " + std::to_string(layout.point_step) + "-byte point record");
    }
    if (!spans.empty() && spans.back().from + spans.back().size == field.offset) {
      spans.back().size += size;
    } else {
      spans.push_back(Span{field.offset, size});
    }
    step += size;
    packed.push_back(packedField);
  }
  if (step == 0) fail("the cloud has no fields");
  const std::string header = pcdHeader(packed, layout.width, layout.height, /*rgbAsUnsigned=*/false) + "DATA binary\n";

  out.write(header);

  const std::size_t points = std::size_t{layout.width} * layout.height;
  const std::size_t perChunk = std::max<std::size_t>(1, kBufferBytes / step);
  std::vector<std::uint8_t> buffer(std::min(perChunk, std::max<std::size_t>(points, 1)) * step);
  for (std::size_t first = 0; first < points; first += perChunk) {
    const std::size_t count = std::min(perChunk, points - first);
    const std::uint8_t* record = records + first * layout.point_step;
    std::uint8_t* to = buffer.data();
    for (std::size_t i = 0; i < count; ++i, record += layout.point_step) {
      for (const Span& span : spans) {
        std::memcpy(to, record + span.from, span.size);
        to += span.size;
      }
    }
    out.write(buffer.data(), count * step);  // one write() of up to 1 MiB
  }
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
