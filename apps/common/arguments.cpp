#include "common/arguments.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace lidar_sgm {
namespace apps {
namespace {

// "-alpha" is an option, "-3" (a negative number) and "-" are not.
bool looksLikeOption(const std::string& token) {
  return token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]));
}

}  // namespace

Arguments::Arguments(int argc, const char* const* argv, const std::set<std::string>& valueOptions,
                     const std::set<std::string>& flagOptions) {
  for (int i = 1; i < argc; ++i) {
    const std::string token = argv[i];
    if (!looksLikeOption(token)) {
      positionals_.push_back(token);
      continue;
    }
    const std::string name = token.substr(token[1] == '-' ? 2 : 1);
    if (flagOptions.count(name)) {
      flags_.insert(name);
    } else if (valueOptions.count(name)) {
      if (i + 1 >= argc) throw std::invalid_argument("option -" + name + " needs a value");
      values_[name] = argv[++i];
    } else {
      throw std::invalid_argument("unknown option " + token + " (see -h)");
    }
  }
}

std::string Arguments::text(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

int Arguments::integer(const std::string& name, int fallback) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const long value = std::strtol(it->second.c_str(), &end, 10);
  if (it->second.empty() || *end != '\0' || value < -1000000000L || value > 1000000000L) {
    throw std::invalid_argument("option -" + name + ": '" + it->second + "' is not an integer");
  }
  return static_cast<int>(value);
}

double Arguments::number(const std::string& name, double fallback) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const double value = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !std::isfinite(value)) {
    throw std::invalid_argument("option -" + name + ": '" + it->second + "' is not a finite number");
  }
  return value;
}

}  // namespace apps
}  // namespace lidar_sgm
