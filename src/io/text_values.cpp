#include "text_values.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include <pcl/PCLPointField.h>

namespace lidar_sgm {
namespace io {
namespace detail {
namespace {

// Casting a double beyond float's range is undefined behaviour: such a value becomes +-inf.
template <typename T>
T narrowReal(double value) {
  if (std::isfinite(value) && std::fabs(value) > static_cast<double>(std::numeric_limits<T>::max())) {
    return std::copysign(std::numeric_limits<T>::infinity(), static_cast<T>(value > 0 ? 1 : -1));
  }
  return static_cast<T>(value);
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

bool parseSigned(const std::string& text, std::int64_t min, std::int64_t max, std::int64_t& value) {
  if (text.empty() || isSpace(text[0])) return false;
  errno = 0;
  char* end = nullptr;
  const long long parsed = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size() || parsed < min || parsed > max) return false;
  value = parsed;
  return true;
}

bool parseUnsigned(const std::string& text, std::uint64_t max, std::uint64_t& value) {
  // strtoull accepts "-1" as 2^64 - 1: a sign is refused first.
  if (text.empty() || text[0] < '0' || text[0] > '9') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long parsed = std::strtoull(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size() || parsed > max) return false;
  value = parsed;
  return true;
}

template <typename T>
bool storeSigned(const std::string& text, std::uint8_t* destination) {
  std::int64_t value = 0;
  if (!parseSigned(text, std::numeric_limits<T>::min(), std::numeric_limits<T>::max(), value)) return false;
  const T typed = static_cast<T>(value);
  std::memcpy(destination, &typed, sizeof typed);
  return true;
}

template <typename T>
bool storeUnsigned(const std::string& text, std::uint8_t* destination) {
  std::uint64_t value = 0;
  if (!parseUnsigned(text, std::numeric_limits<T>::max(), value)) return false;
  const T typed = static_cast<T>(value);
  std::memcpy(destination, &typed, sizeof typed);
  return true;
}

template <typename T>
bool storeReal(std::string_view token, std::uint8_t* destination) {
  double value = 0.0;
  if (!parseReal(token, value)) return false;
  const T typed = narrowReal<T>(value);
  std::memcpy(destination, &typed, sizeof typed);
  return true;
}

}  // namespace

std::vector<std::string_view> splitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

bool parseCount(std::string_view token, std::uint64_t max, std::uint64_t& value) {
  return parseUnsigned(std::string(token), max, value);
}

bool parseReal(std::string_view token, double& value) {
  const std::string text(token);
  if (text.empty() || isSpace(text[0])) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);  // ERANGE (1e400, 1e-400) keeps strtod's +-inf or 0
  return end != text.c_str() && end == text.c_str() + text.size();
}

std::size_t datatypeSize(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
    case pcl::PCLPointField::UINT8: return 1;
    case pcl::PCLPointField::INT16:
    case pcl::PCLPointField::UINT16: return 2;
    case pcl::PCLPointField::INT32:
    case pcl::PCLPointField::UINT32:
    case pcl::PCLPointField::FLOAT32: return 4;
    case pcl::PCLPointField::INT64:
    case pcl::PCLPointField::UINT64:
    case pcl::PCLPointField::FLOAT64: return 8;
    default: return 0;
  }
}

bool parseValue(std::string_view token, std::uint8_t datatype, std::uint8_t* destination) {
  const std::string text(token);
  switch (datatype) {
    case pcl::PCLPointField::INT8: return storeSigned<std::int8_t>(text, destination);
    case pcl::PCLPointField::UINT8: return storeUnsigned<std::uint8_t>(text, destination);
    case pcl::PCLPointField::INT16: return storeSigned<std::int16_t>(text, destination);
    case pcl::PCLPointField::UINT16: return storeUnsigned<std::uint16_t>(text, destination);
    case pcl::PCLPointField::INT32: return storeSigned<std::int32_t>(text, destination);
    case pcl::PCLPointField::UINT32: return storeUnsigned<std::uint32_t>(text, destination);
    case pcl::PCLPointField::INT64: return storeSigned<std::int64_t>(text, destination);
    case pcl::PCLPointField::UINT64: return storeUnsigned<std::uint64_t>(text, destination);
    case pcl::PCLPointField::FLOAT32: return storeReal<float>(token, destination);
    case pcl::PCLPointField::FLOAT64: return storeReal<double>(token, destination);
    default: return false;
  }
}

float narrowToFloat(double value) { return narrowReal<float>(value); }

const char* datatypeName(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: return "int8";
    case pcl::PCLPointField::UINT8: return "uint8";
    case pcl::PCLPointField::INT16: return "int16";
    case pcl::PCLPointField::UINT16: return "uint16";
    case pcl::PCLPointField::INT32: return "int32";
    case pcl::PCLPointField::UINT32: return "uint32";
    case pcl::PCLPointField::INT64: return "int64";
    case pcl::PCLPointField::UINT64: return "uint64";
    case pcl::PCLPointField::FLOAT32: return "float32";
    case pcl::PCLPointField::FLOAT64: return "float64";
    case pcl::PCLPointField::BOOL: return "bool";
    default: return "unknown";
  }
}

}  // namespace detail
}  // namespace io
}  // namespace lidar_sgm
