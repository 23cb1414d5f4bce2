#pragma once
// PCL-tool-style command lines ("-alpha 0.7", "-keep_organized") for CLI11, which accepts only
// single-letter options after one dash (2.1-2.3 reject "-alpha" as an option name).

#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace lidar_sgm {
namespace apps {

/// The arguments (without the program name) as CLI11 parses them unambiguously: an option
/// registered in `app` with a long name, given as "-name" or "--name", becomes "--name"; one that
/// takes a value becomes "--name=VALUE" with the next argument as its value, whatever that looks
/// like ("-min_disparity -16", "-out -dir"). Everything else is copied as it is: positionals,
/// negative numbers, unknown options (CLI11 then reports them), single-letter options ("-h") and
/// every argument after "--". Throws std::invalid_argument "option -name needs a value" when a
/// value-taking option is last or followed by another registered option.
std::vector<std::string> toCli11Arguments(const CLI::App& app, const std::vector<std::string>& arguments);

}  // namespace apps
}  // namespace lidar_sgm
