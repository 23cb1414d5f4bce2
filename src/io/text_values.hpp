#pragma once
/// @file text_values.hpp  (private) Strict text to number conversions for the PCD and PLY
/// readers: the whole token must be the number, in range for its type (strtod alone reads
/// "7abc" as 7, and PCL read "abc" as 0).

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace lidar_sgm {
namespace io {
namespace detail {

/// The whitespace-separated tokens of `line`.
std::vector<std::string_view> splitWhitespace(std::string_view line);

/// A decimal count without sign, at most `max`; false otherwise.
bool parseCount(std::string_view token, std::uint64_t max, std::uint64_t& value);

/// A finite or non-finite real ("nan" is how PCL writes a missing point).
bool parseReal(std::string_view token, double& value);

/// Bytes of one value of a pcl::PCLPointField datatype that PCD and PLY files hold (0 for another:
/// an unknown one, or bool, which neither format has).
std::size_t datatypeSize(std::uint8_t datatype);

/// Parses `token` as one value of a pcl::PCLPointField `datatype` and stores it, in host order,
/// at `destination`; false when it is not such a value (out of range, not a number, trailing text).
bool parseValue(std::string_view token, std::uint8_t datatype, std::uint8_t* destination);

/// `value` as float; beyond float's range (where a plain cast is undefined) +-inf.
float narrowToFloat(double value);

/// pcl::PCLPointField datatype name, for messages.
const char* datatypeName(std::uint8_t datatype);

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
