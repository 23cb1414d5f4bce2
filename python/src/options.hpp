#pragma once
// Keyword parameters -> a configured Densifier, through the library's option table
// (lidar_sgm/pipeline/config_options.hpp): the tools' names (without the dash), defaults, checks
// and messages, with no command line in between.
//   Densifier(calib, alpha=0.7, no_lr_check=True)  ==  lidar_sgm_densify -alpha 0.7 -no_lr_check

#include <string>

#include <pybind11/pybind11.h>

#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace python {

/// Which parameters a front end takes: the whole frame's (densify) or the matcher's (match).
enum class OptionSet { Densify, Match };

/// Sets `densifier` up from `parameters` as lidar_sgm_densify (Densify) or lidar_sgm_disparity
/// (Match) would from the same options. Flags (no_lr_check, keep_organized, ...) take True /
/// False; None leaves a parameter at its default. ValueError for an unknown name or a bad value.
void configure(Densifier& densifier, const pybind11::dict& parameters, OptionSet set);

/// The parameters' help, with their defaults, for the docstrings.
std::string parametersHelp(OptionSet set);

/// name -> default of every parameter `set` takes (flags False), for lidar_sgm.options().
pybind11::dict parameterDefaults(OptionSet set);

}  // namespace python
}  // namespace lidar_sgm
