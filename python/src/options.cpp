#include "options.hpp"

#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "lidar_sgm/pipeline/config_options.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;

namespace {

OptionScope scopeOf(OptionSet set) { return set == OptionSet::Densify ? OptionScope::Cloud : OptionScope::Disparity; }

std::string known(OptionSet set) {
  std::set<std::string> names;  // sorted, as a reader looks for a name
  for (const DensifierOption* o : densifierOptions(scopeOf(set))) names.insert(o->name);
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

const DensifierOption* optionOf(const std::string& name, OptionSet set) {
  for (const DensifierOption* o : densifierOptions(scopeOf(set))) {
    if (name == o->name) return o;
  }
  throw std::invalid_argument("unknown parameter '" + name + "' (known: " + known(set) + ")");
}

/// A keyword's value as the option's text. Floats go through repr(), the shortest text that
/// reads back to the same double, so a value means what the same number on the command line does.
std::string valueText(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (!py::isinstance<py::bool_>(value)) {
    if (py::hasattr(value, "__index__")) return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
    if (py::hasattr(value, "__float__")) return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  }
  throw std::invalid_argument("parameter " + name + ": expected a number or text, got " +
                              py::repr(value).cast<std::string>());
}

}  // namespace

void configure(Densifier& densifier, const py::dict& parameters, OptionSet set) {
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  for (const auto& [key, value] : parameters) {
    const std::string name = py::str(key);
    const DensifierOption* option = optionOf(name, set);
    if (value.is_none()) continue;
    if (option->kind != OptionKind::Flag) {
      values[name] = valueText(name, value);
    } else if (!py::isinstance<py::bool_>(value)) {
      throw std::invalid_argument("parameter " + name + ": a flag, expected True or False, got " +
                                  py::repr(value).cast<std::string>());
    } else if (value.cast<bool>()) {
      flags.insert(name);
    }
  }
  DensifierConfig config = configFromOptions(values, flags);
  if (set == OptionSet::Match) config.computeCloud = false;  // as lidar_sgm_disparity: the disparity only
  densifier.setConfig(config);
}

std::string parametersHelp(OptionSet set) {
  const OptionScope scope = scopeOf(set);
  return "Parameters: the options of the command-line tools, as keywords without the dash\n"
         "(-alpha 0.7 -> alpha=0.7; flags take True/False: -no_lr_check -> no_lr_check=True;\n"
         "None or absent = the default):\n" +
         optionsHelp(OptionGroup::Method, scope) + optionsHelp(OptionGroup::Speed, scope) +
         optionsHelp(OptionGroup::Filters, scope) + optionsHelp(OptionGroup::Output, scope);
}

py::dict parameterDefaults(OptionSet set) {
  const DensifierConfig defaults;
  py::dict out;
  for (const DensifierOption* o : densifierOptions(scopeOf(set))) {
    const std::string text = o->value(defaults);
    switch (o->kind) {
      case OptionKind::Flag: out[o->name] = py::bool_(text == "true"); break;
      case OptionKind::Integer: out[o->name] = py::int_(parseOptionInteger(o->name, text)); break;
      case OptionKind::Number: out[o->name] = py::float_(parseOptionNumber(o->name, text)); break;
      case OptionKind::Choice: out[o->name] = py::str(text); break;
    }
  }
  return out;
}

}  // namespace python
}  // namespace lidar_sgm
