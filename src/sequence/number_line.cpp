#include "number_line.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace lidar_sgm {
namespace sequence {

std::vector<double> numbersOfLine(const std::string& line, const std::string& where) {
  std::istringstream fields(line);
  std::vector<double> numbers;
  for (std::string field; fields >> field;) {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0') throw std::invalid_argument(where + ": '" + field + "' is not a number");
    if (!std::isfinite(value) || errno == ERANGE) {
      throw std::invalid_argument(where + ": '" + field + "' is not a finite number");
    }
    numbers.push_back(value);
  }
  return numbers;
}

}  // namespace sequence
}  // namespace lidar_sgm
