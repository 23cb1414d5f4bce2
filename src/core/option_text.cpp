#include "lidar_sgm/core/option_text.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace lidar_sgm {

int parseOptionInteger(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < -1000000000L || value > 1000000000L) {
    throw std::invalid_argument("option -" + name + ": '" + text + "' is not an integer");
  }
  return static_cast<int>(value);
}

double parseOptionNumber(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value)) {
    throw std::invalid_argument("option -" + name + ": '" + text + "' is not a finite number");
  }
  return value;
}

}  // namespace lidar_sgm
