#pragma once
// The matcher's command-line options, shared by every tool that runs LiDAR-SGM.

#include <set>
#include <string>

#include "common/arguments.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"

namespace lidar_sgm {
namespace apps {

/// Option names taking a value (-alpha 0.7 ...) and flags (-no_lr_check ...).
const std::set<std::string>& sgmValueOptions();
const std::set<std::string>& sgmFlagOptions();
/// The help lines for those options, with their defaults, by help group: the method's (cost,
/// range, aggregation, checks), the speed's (-scale, -threads, -backend, -no_confidence) and the
/// confidence filter's (-min_confidence); sgmOptionsHelp() is all three.
std::string sgmMethodHelp();
std::string sgmSpeedHelp();
std::string sgmConfidenceHelp();
std::string sgmOptionsHelp();
/// Parameters from the options, validated (std::invalid_argument names the bad one).
Parameters parametersFrom(const Arguments& args);
/// Whether the search range is the fixed one of the options (-disparity_range fixed, or
/// -num_disparities / -min_disparity given without -disparity_range lidar) rather than the
/// frame's LiDAR's (the default). Throws std::invalid_argument for another -disparity_range.
bool fixedDisparityRange(const Arguments& args);
/// The -backend option (default auto), checked against the backends built into this library, so
/// that a tool refuses it before reading any file.
Backend backendFrom(const Arguments& args);
/// The -min_confidence option (default kDefaultMinConfidence; 0 with -no_confidence), in [0, 1].
double minConfidenceFrom(const Arguments& args);
/// The union of two option sets.
std::set<std::string> joined(std::set<std::string> a, const std::set<std::string>& b);

}  // namespace apps
}  // namespace lidar_sgm
