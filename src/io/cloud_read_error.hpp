#pragma once
/// @file cloud_read_error.hpp  (private) The one form of every cloud reader's error, and size
/// arithmetic that cannot wrap: a header's counts are multiplied before anything is allocated.

#include <cstdint>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace io {
namespace detail {

[[noreturn]] inline void failCloudRead(const std::string& source, const std::string& problem) {
  throw std::runtime_error("cannot read cloud '" + source + "': " + problem);
}

/// a * b, or UINT64_MAX when it does not fit: such a product never fits in any file.
inline std::uint64_t saturatingMultiply(std::uint64_t a, std::uint64_t b) {
  std::uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

inline std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
  std::uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? UINT64_MAX : sum;
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
