#pragma once
// The Densifier's output-filter options (sky, isolated points) and its check of the pair's
// orientation, shared by the tools that run it.

#include <set>
#include <string>

#include "common/arguments.hpp"
#include "lidar_sgm/pipeline/output_filters.hpp"

namespace lidar_sgm {
namespace apps {

/// Option names taking a value (-outlier_min_neighbours 4 ...) and flags (-no_sky_filter ...).
const std::set<std::string>& filterValueOptions();
const std::set<std::string>& filterFlagOptions();
/// The help lines for those options, with their defaults.
std::string filterOptionsHelp();
/// The filter options from the command line, validated (std::invalid_argument names the bad one).
OutputFilterOptions outputFiltersFrom(const Arguments& args);
/// Whether a pair that looks swapped is refused (true unless -no_pair_check).
bool pairCheckFrom(const Arguments& args);

}  // namespace apps
}  // namespace lidar_sgm
