#pragma once
/// @file field_text.hpp  (private) One value of a point field as text, the way C++ streams write
/// it (what PCL's ASCII writers produce, and what readers parse back): integers in decimal,
/// floating-point values as printf's "%.<precision>g", NaN as "nan" (its sign dropped).

#include <cstdint>
#include <string>

#include <pcl/PCLPointCloud2.h>

namespace lidar_sgm {
namespace io {
namespace detail {

/// Floats need 9 significant digits to read back exactly (C++ streams' default is 6, PCL's 8).
constexpr int kAsciiPrecision = 9;

/// Appends the value of PCL type `datatype` stored at `bytes` (unaligned) to `out`; false for a
/// type this writer does not know (nothing appended).
bool appendFieldValue(std::string& out, std::uint8_t datatype, const std::uint8_t* bytes, int precision);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
