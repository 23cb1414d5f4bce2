#include "common/config_arguments.hpp"

#include <map>

namespace lidar_sgm {
namespace apps {
namespace {

std::set<std::string> names(OptionScope scope, bool flags) {
  std::set<std::string> out;
  for (const DensifierOption* o : densifierOptions(scope)) {
    if ((o->kind == OptionKind::Flag) == flags) out.insert(o->name);
  }
  return out;
}

}  // namespace

std::set<std::string> configValueOptions(OptionScope scope) { return names(scope, false); }

std::set<std::string> configFlagOptions(OptionScope scope) { return names(scope, true); }

DensifierConfig configFrom(const Arguments& args, OptionScope scope) {
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  for (const std::string& name : configValueOptions(scope)) {
    if (args.has(name)) values[name] = args.text(name, "");
  }
  for (const std::string& name : configFlagOptions(scope)) {
    if (args.has(name)) flags.insert(name);
  }
  return configFromOptions(values, flags);
}

}  // namespace apps
}  // namespace lidar_sgm
