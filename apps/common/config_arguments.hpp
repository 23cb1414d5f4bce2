#pragma once
// The command line's side of the option table (lidar_sgm/pipeline/config_options.hpp): the names
// a tool registers with its parser and the DensifierConfig a command line gives (the help of each
// group is the table's own optionsHelp). The table holds the names, defaults, checks and help.

#include <set>
#include <string>

#include "common/arguments.hpp"
#include "lidar_sgm/pipeline/config_options.hpp"

namespace lidar_sgm {
namespace apps {

/// The table's options acting in `scope`: those taking a value, and the flags.
std::set<std::string> configValueOptions(OptionScope scope);
std::set<std::string> configFlagOptions(OptionScope scope);

/// The configuration the command line gives: the table's options in `args` (the tool's own
/// options are left to it) over the default. std::invalid_argument names the bad option.
DensifierConfig configFrom(const Arguments& args, OptionScope scope);

}  // namespace apps
}  // namespace lidar_sgm
