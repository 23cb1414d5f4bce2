#include "common/pcl_style_options.hpp"

#include <map>
#include <stdexcept>

#include <CLI/CLI.hpp>

namespace lidar_sgm {
namespace apps {
namespace {

/// "-alpha", "--alpha", "-alpha=0.7" -> "alpha"; "" when `token` is not a long option's spelling.
std::string optionName(const std::string& token) {
  if (token.size() < 2 || token[0] != '-') return "";
  const std::size_t start = token[1] == '-' ? 2 : 1;
  return token.substr(start, token.find('=') == std::string::npos ? std::string::npos : token.find('=') - start);
}

}  // namespace

std::vector<std::string> toCli11Arguments(const CLI::App& app, const std::vector<std::string>& arguments) {
  // Long name -> whether it takes a value (flags expect none).
  std::map<std::string, bool> takesValue;
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_positional()) continue;
    for (const std::string& name : option->get_lnames()) takesValue[name] = option->get_expected_max() > 0;
  }
  const auto registered = [&](const std::string& token) { return takesValue.count(optionName(token)) > 0; };

  std::vector<std::string> out;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& token = arguments[i];
    if (token == "--") {
      // CLI11's end of options: the rest are positionals, as the user wrote them.
      out.insert(out.end(), arguments.begin() + static_cast<std::ptrdiff_t>(i), arguments.end());
      break;
    }
    if (!registered(token)) {
      out.push_back(token);
      continue;
    }
    const std::string name = optionName(token);
    const std::size_t equals = token.find('=');
    if (!takesValue[name] || equals != std::string::npos) {
      out.push_back("--" + name + (equals == std::string::npos ? "" : token.substr(equals)));
      continue;
    }
    if (i + 1 >= arguments.size() || registered(arguments[i + 1])) {
      throw std::invalid_argument("option -" + name + " needs a value");
    }
    const std::string& value = arguments[++i];
    // "--name=" would leave CLI11 looking for the value in the next argument.
    if (value.empty()) {
      out.push_back("--" + name);
      out.push_back(value);
    } else {
      out.push_back("--" + name + "=" + value);
    }
  }
  return out;
}

}  // namespace apps
}  // namespace lidar_sgm
