#include "common/help_layout.hpp"

namespace lidar_sgm {
namespace apps {

std::string helpText(const std::string& usage, const std::vector<HelpGroup>& groups,
                     const std::vector<HelpExample>& examples) {
  std::string text = usage;
  for (const HelpGroup& group : groups) {
    if (group.lines.empty()) continue;
    text += "\n" + group.heading + ":\n" + group.lines;
  }
  text +=
      "\nHelp:\n"
      "  -h, --help               this help\n"
      "  --version                the tool's name and version\n"
      "Every option also takes the GNU spelling: --name VALUE, --name=VALUE.\n";
  if (!examples.empty()) {
    // Last, where a reader scrolling up from the prompt sees them first.
    text += "\nExamples (data/sample/ is the repository's sample frame):\n";
    for (const HelpExample& example : examples) text += "  " + example.what + "\n    " + example.command + "\n";
  }
  return text;
}

}  // namespace apps
}  // namespace lidar_sgm
