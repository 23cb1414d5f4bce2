#pragma once
// The one layout of every tool's --help: what the tool does, its options under headings (inputs,
// outputs, method, speed, filters, ...), then examples of real use. A tool adds an option to the
// group it belongs to; a new group is one more entry.

#include <string>
#include <vector>

namespace lidar_sgm {
namespace apps {

/// Options under one heading ("Inputs", "Outputs", "Method", "Speed", "Filters", ...): their help
/// lines, each "  -name VALUE   what it does".
struct HelpGroup {
  std::string heading;
  std::string lines;
};

/// A command that really works, run from the repository's root (the tests run them): `what` says
/// what it does.
struct HelpExample {
  std::string what;
  std::string command;
};

/// `usage` (the syntax line and what the tool does), then every non-empty group as "Heading:" and
/// its lines, the -h/--version lines, the GNU-spelling note, and last "Examples:" with each
/// example's description and command.
std::string helpText(const std::string& usage, const std::vector<HelpGroup>& groups,
                     const std::vector<HelpExample>& examples);

}  // namespace apps
}  // namespace lidar_sgm
