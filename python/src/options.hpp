#pragma once
// Keyword parameters -> a configured Densifier, through the densify tool's own option code
// (apps/common, apps/densify): the same names (without the dash), defaults, checks and messages.
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

}  // namespace python
}  // namespace lidar_sgm
