#pragma once
// PCL-tool-style command lines: positional files and single-dash options ("-alpha 0.7", "-h"),
// parsed by CLI11; "--alpha 0.7", "--alpha=0.7", "--help" and "--version" work too.

#include <map>
#include <set>
#include <string>
#include <vector>

namespace lidar_sgm {
namespace apps {

class Arguments {
 public:
  /// `valueOptions` take one value, `flagOptions` none (names without dashes; the last of a
  /// repeated option wins). -h, -help, --help and --version are always known. Throws
  /// std::invalid_argument for an unknown option or an option without its value.
  Arguments(int argc, const char* const* argv, const std::set<std::string>& valueOptions,
            const std::set<std::string>& flagOptions);

  const std::vector<std::string>& positionals() const { return positionals_; }
  bool has(const std::string& name) const { return values_.count(name) > 0 || flags_.count(name) > 0; }
  /// -h / -help / --help: the tool prints its help and does nothing else.
  bool helpRequested() const { return help_; }
  /// --version (or -version): the tool prints its name and version and does nothing else.
  bool versionRequested() const { return version_; }

  /// The option's value, or `fallback` when absent. A malformed number throws
  /// std::invalid_argument naming the option and the text.
  std::string text(const std::string& name, const std::string& fallback) const;
  int integer(const std::string& name, int fallback) const;
  double number(const std::string& name, double fallback) const;

  /// Every value option given (name -> value) and every flag given.
  const std::map<std::string, std::string>& values() const { return values_; }
  const std::set<std::string>& flags() const { return flags_; }

 private:
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
  bool help_ = false;
  bool version_ = false;
};

/// The union of two option sets.
std::set<std::string> joined(std::set<std::string> a, const std::set<std::string>& b);

}  // namespace apps
}  // namespace lidar_sgm
