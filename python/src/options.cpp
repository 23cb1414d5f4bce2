#include "options.hpp"

#include <set>
#include <stdexcept>
#include <vector>

#include "common/arguments.hpp"
#include "common/filter_options.hpp"
#include "common/sgm_options.hpp"
#include "densify/densify_options.hpp"

namespace lidar_sgm {
namespace python {

namespace py = pybind11;
using apps::joined;

namespace {

// lidar_sgm_densify's method and cloud options, minus the file ones (-format, -image_size: the
// calibration or the images give the size).
std::set<std::string> valueOptions(OptionSet set) {
  std::set<std::string> names = joined(apps::sgmValueOptions(), apps::filterValueOptions());
  if (set == OptionSet::Densify) names = joined(names, {"frame", "max_depth", "stride"});
  return names;
}

std::set<std::string> flagOptions(OptionSet set) {
  std::set<std::string> names = joined(joined(apps::sgmFlagOptions(), apps::filterFlagOptions()), {"no_crop_to_scan"});
  if (set == OptionSet::Densify) names = joined(names, {"keep_organized", "no_occlusion_filter"});
  return names;
}

std::string listed(const std::set<std::string>& a, const std::set<std::string>& b) {
  std::string text;
  for (const std::string& name : joined(a, b)) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// A keyword's value as the command line would spell it. Floats go through repr(), the shortest
/// text that reads back to the same double.
std::string optionText(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) {
    throw std::invalid_argument("parameter " + name + ": expected a number or text, got " +
                                py::repr(value).cast<std::string>());
  }
  if (py::hasattr(value, "__index__")) return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
  if (py::hasattr(value, "__float__")) return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  throw std::invalid_argument("parameter " + name + ": expected a number or text, got " +
                              py::repr(value).cast<std::string>());
}

/// The keywords as a command line: "-name value" and "-flag".
std::vector<std::string> commandLine(const py::dict& parameters, OptionSet set) {
  const std::set<std::string> values = valueOptions(set);
  const std::set<std::string> flags = flagOptions(set);
  std::vector<std::string> line{"lidar_sgm"};
  for (const auto& [key, value] : parameters) {
    const std::string name = py::str(key);
    if (value.is_none()) continue;
    if (values.count(name) > 0) {
      line.push_back("-" + name);
      line.push_back(optionText(name, value));
    } else if (flags.count(name) > 0) {
      if (!py::isinstance<py::bool_>(value)) {
        throw std::invalid_argument("parameter " + name + ": a flag, expected True or False, got " +
                                    py::repr(value).cast<std::string>());
      }
      if (value.cast<bool>()) line.push_back("-" + name);
    } else {
      throw std::invalid_argument("unknown parameter '" + name + "' (known: " + listed(values, flags) + ")");
    }
  }
  return line;
}

}  // namespace

void configure(Densifier& densifier, const py::dict& parameters, OptionSet set) {
  const std::vector<std::string> line = commandLine(parameters, set);
  std::vector<const char*> argv;
  for (const std::string& word : line) argv.push_back(word.c_str());
  const apps::Arguments args(static_cast<int>(argv.size()), argv.data(), valueOptions(set), flagOptions(set));
  // As apps::configureDensification does for the tool's SGMDensification (densify_options.hpp).
  densifier.setParameters(apps::parametersFrom(args));
  densifier.setBackend(apps::backendFrom(args));
  densifier.setDisparityRangeMode(apps::fixedDisparityRange(args) ? DisparityRangeMode::Fixed
                                                                  : DisparityRangeMode::FromLidar);
  densifier.setCropToScan(!args.has("no_crop_to_scan"));
  densifier.setMinConfidence(apps::minConfidenceFrom(args));
  densifier.setOutputFilters(apps::outputFiltersFrom(args));
  densifier.setPairCheck(apps::pairCheckFrom(args));
  if (set == OptionSet::Match) {
    densifier.setComputeCloud(false);  // as lidar_sgm_disparity: the disparity only
    return;
  }
  geometry::ProjectionOptions projection;
  projection.occlusion.enabled = !args.has("no_occlusion_filter");
  densifier.setProjectionOptions(projection);
  const apps::OutputOptions out = apps::outputOptionsFrom(args);
  geometry::ReprojectionOptions& reprojection = densifier.reprojectionOptions();
  reprojection.keepOrganized = args.has("keep_organized");
  reprojection.frame = out.frame;
  reprojection.maxDepth = out.maxDepth;
  reprojection.stride = out.stride;
}

std::string parametersHelp(OptionSet set) {
  std::string help =
      "Parameters: the options of the command-line tools, as keywords without the dash\n"
      "(-alpha 0.7 -> alpha=0.7; flags take True/False: -no_lr_check -> no_lr_check=True;\n"
      "None or absent = the default):\n" +
      apps::sgmOptionsHelp() + apps::filterOptionsHelp();
  if (set == OptionSet::Densify) {
    const geometry::ReprojectionOptions reprojection;
    help += "  -frame lidar|camera      the points' frame (default: lidar, the input's frame)\n"
            "  -max_depth M             drop points (and depth) deeper than M metres, 0 = keep all (default: " +
            std::to_string(static_cast<int>(reprojection.maxDepth)) +
            ")\n"
            "  -stride S                every S-th pixel in x and y (default: 1)\n"
            "  -keep_organized          one point per pixel, NaN where there is none (default: valid points only)\n"
            "  -no_occlusion_filter     keep LiDAR points hidden from the camera (default: dropped)\n";
  }
  help += "  -no_crop_to_scan         LiDAR-only: keep pixels above the scan's top / below its bottom beam\n";
  return help;
}

}  // namespace python
}  // namespace lidar_sgm
