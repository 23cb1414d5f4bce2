#include "common/arguments.hpp"

#include <cctype>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "common/pcl_style_options.hpp"
#include "lidar_sgm/core/option_text.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

// "-alpha" and "--alpha" are options, "-3" (a negative number) and "-" are not.
bool looksLikeOption(const std::string& token) {
  const std::size_t start = token.rfind("--", 0) == 0 ? 2 : 1;
  return token.size() > start && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[start]));
}

}  // namespace

Arguments::Arguments(int argc, const char* const* argv, const std::set<std::string>& valueOptions,
                     const std::set<std::string>& flagOptions) {
  CLI::App app;
  // The tools print their own help (PCL style, every default); here -h is a flag like any other.
  app.set_help_flag();
  app.allow_extras();  // reported below, in our words
  CLI::Option* help = app.add_flag("-h,--help");
  CLI::Option* version = app.add_flag("--version");
  std::map<std::string, std::string> values;
  std::map<std::string, CLI::Option*> flags;
  for (const std::string& name : valueOptions) {
    app.add_option("--" + name, values[name])->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  for (const std::string& name : flagOptions) flags[name] = app.add_flag("--" + name);
  app.add_option("files", positionals_);

  std::vector<std::string> arguments(argv + 1, argv + argc);
  arguments = toCli11Arguments(app, arguments);
  // CLI11 parses a reversed vector (it pops from the back).
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument(e.what());
  }
  help_ = help->count() > 0;
  version_ = version->count() > 0;
  if (help_ || version_) return;  // those answer whatever else the line holds
  for (const std::string& extra : app.remaining()) {
    if (extra == "--") continue;  // CLI11 lists the end-of-options mark among the extras
    if (looksLikeOption(extra)) throw std::invalid_argument("unknown option " + extra + " (see -h)");
    throw std::invalid_argument("unexpected argument '" + extra + "' (see -h)");
  }
  for (const std::string& name : valueOptions) {
    if (app.get_option("--" + name)->count() > 0) values_[name] = values[name];
  }
  for (const auto& [name, option] : flags) {
    if (option->count() > 0) flags_.insert(name);
  }
}

std::string Arguments::text(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

int Arguments::integer(const std::string& name, int fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : parseOptionInteger(name, it->second);
}

double Arguments::number(const std::string& name, double fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : parseOptionNumber(name, it->second);
}

std::set<std::string> joined(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

}  // namespace apps
}  // namespace lidar_sgm
