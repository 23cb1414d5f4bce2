#include "field_text.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

template <typename T>
T load(const std::uint8_t* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <typename T>
void appendInteger(std::string& out, T value) {
  char text[24];
  const std::to_chars_result end = std::to_chars(text, text + sizeof(text), value);
  out.append(text, end.ptr);
}

// std::to_chars(general, p) is printf's "%.pg", which is what a stream of precision p writes.
template <typename T>
void appendReal(std::string& out, T value, int precision) {
  if (std::isnan(value)) {
    out += "nan";
    return;
  }
  char text[64];
  const std::to_chars_result end =
      std::to_chars(text, text + sizeof(text), value, std::chars_format::general, precision);
  out.append(text, end.ptr);
}

}  // namespace

bool appendFieldValue(std::string& out, std::uint8_t datatype, const std::uint8_t* bytes, int precision) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: appendInteger(out, static_cast<int>(load<std::int8_t>(bytes))); return true;
    case pcl::PCLPointField::UINT8: appendInteger(out, static_cast<int>(load<std::uint8_t>(bytes))); return true;
    case pcl::PCLPointField::INT16: appendInteger(out, load<std::int16_t>(bytes)); return true;
    case pcl::PCLPointField::UINT16: appendInteger(out, load<std::uint16_t>(bytes)); return true;
    case pcl::PCLPointField::INT32: appendInteger(out, load<std::int32_t>(bytes)); return true;
    case pcl::PCLPointField::UINT32: appendInteger(out, load<std::uint32_t>(bytes)); return true;
    case pcl::PCLPointField::INT64: appendInteger(out, load<std::int64_t>(bytes)); return true;
    case pcl::PCLPointField::UINT64: appendInteger(out, load<std::uint64_t>(bytes)); return true;
    case pcl::PCLPointField::FLOAT32: appendReal(out, load<float>(bytes), precision); return true;
    case pcl::PCLPointField::FLOAT64: appendReal(out, load<double>(bytes), precision); return true;
    default: return false;
  }
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
