#pragma once
/// @file config_options.hpp  The one table of the Densifier's options: each option's name, kind,
/// group, where it acts, help and how it reads and writes a DensifierConfig. The command-line
/// tools register these names with their parser, the Python module maps keyword arguments onto
/// them, and every help text is rendered from here; the defaults are read from a
/// default-constructed DensifierConfig. Adding an option is one entry in src/pipeline/config_options.cpp.
///
/// @code
///   lidar_sgm::DensifierConfig config = lidar_sgm::configFromOptions({{"alpha", "0.5"}}, {"no_lr_check"});
///   densifier.setConfig(config);
/// @endcode

#include <map>
#include <set>
#include <string>
#include <vector>

#include "lidar_sgm/core/option_text.hpp"
#include "lidar_sgm/pipeline/densifier_config.hpp"

namespace lidar_sgm {

/// How an option is given: a flag takes no value ("-no_lr_check"); the others one value.
enum class OptionKind { Flag, Integer, Number, Choice };

/// The heading an option is listed under in every help text.
enum class OptionGroup { Method, Speed, Filters, Output };

/// Where an option acts: on the disparity (every front end: the tools, Python's match and
/// Densifier, the evaluation) or only on the depth and cloud made from it (the front ends that
/// reproject).
enum class OptionScope { Disparity, Cloud };

struct DensifierOption {
  const char* name;       ///< without the dash: "alpha"
  OptionKind kind;
  const char* valueName;  ///< the value's placeholder in help ("A", "4|8"); empty for flags
  OptionGroup group;
  OptionScope scope;
  /// What it does. Value options get " (default: X)" appended by the help; a flag says in its
  /// text what happens without it.
  std::string help;
  /// Reads `text` into `config` (flags: "true" or "false"); std::invalid_argument
  /// "option -name: ..." for a value that is not of the option's kind or outside its range.
  void (*apply)(DensifierConfig& config, const std::string& text);
  /// The option's value in `config` as text, in the form apply() reads ("true"/"false" for flags).
  std::string (*value)(const DensifierConfig& config);
};

/// Every option, in help order.
const std::vector<DensifierOption>& densifierOptions();
/// The options acting in `scope` (Cloud: all of them; Disparity: those on the disparity).
std::vector<const DensifierOption*> densifierOptions(OptionScope scope);
/// The option named `name`, or null.
const DensifierOption* findDensifierOption(const std::string& name);
/// The default of `option` as text, from DensifierConfig{}.
std::string defaultValue(const DensifierOption& option);

/// A DensifierConfig from options given by name: `values` (name -> text) and `flags` (the flags
/// given), applied in table order to `base` (default: the shipped default), then the rules that
/// join options: -num_disparities or -min_disparity without -disparity_range mean a fixed range;
/// -no_confidence without -min_confidence means a minimum of 0. Validated (validate()).
/// std::invalid_argument for an unknown name, a bad value or an invalid result, naming the option.
DensifierConfig configFromOptions(const std::map<std::string, std::string>& values, const std::set<std::string>& flags,
                                  const DensifierConfig& base = DensifierConfig());

/// The help lines of the options of `group` acting in `scope`, in the tools' layout: "  -name
/// VALUE" in a 27-column field, the help wrapped at 112 columns, then " (default: X)".
std::string optionsHelp(OptionGroup group, OptionScope scope);

}  // namespace lidar_sgm
