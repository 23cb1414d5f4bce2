#include "common/filter_options.hpp"

#include <cstdio>

namespace lidar_sgm {
namespace apps {

const std::set<std::string>& filterValueOptions() {
  static const std::set<std::string> options{"sky_texture", "outlier_min_neighbours"};
  return options;
}

const std::set<std::string>& filterFlagOptions() {
  static const std::set<std::string> flags{"no_sky_filter", "no_outlier_filter", "no_pair_check"};
  return flags;
}

std::string filterOptionsHelp() {
  const OutputFilterOptions d;
  char text[1600];
  std::snprintf(text, sizeof(text),
                "  -no_sky_filter           keep the sky: pixels above the scan's top return, in a bright (>= %d) blank\n"
                "                           patch of the left image connected to its top row (default: removed, with LiDAR)\n"
                "  -sky_texture T           blank = mean |gradient| of the left image below T levels/px in a %dx%d\n"
                "                           window (default: %g)\n"
                "  -no_outlier_filter       keep isolated and flying points (default: removed, with LiDAR)\n"
                "  -outlier_min_neighbours N  a point needs N of its %d neighbours within %g %% of its disparity\n"
                "                           (at least %g px), 0 = off (default: %d)\n"
                "  -no_pair_check           match a pair that looks swapped (default: refused when the LiDAR, or\n"
                "                           without it most matches, find the right image on the wrong side)\n",
                d.sky.brightLevel, 2 * d.sky.textureRadius + 1, 2 * d.sky.textureRadius + 1, d.sky.textureThreshold,
                (2 * d.outliers.radius + 1) * (2 * d.outliers.radius + 1) - 1, 100.0 * d.outliers.relativeTolerance,
                d.outliers.minTolerance, d.outliers.minNeighbours);
  return text;
}

OutputFilterOptions outputFiltersFrom(const Arguments& args) {
  OutputFilterOptions o;
  o.sky.enabled = !args.has("no_sky_filter");
  o.sky.textureThreshold = args.number("sky_texture", o.sky.textureThreshold);
  o.outliers.enabled = !args.has("no_outlier_filter");
  o.outliers.minNeighbours = args.integer("outlier_min_neighbours", o.outliers.minNeighbours);
  validate(o.sky);
  validate(o.outliers);
  return o;
}

bool pairCheckFrom(const Arguments& args) { return !args.has("no_pair_check"); }

}  // namespace apps
}  // namespace lidar_sgm
