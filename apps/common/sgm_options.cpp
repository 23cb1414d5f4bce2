#include "common/sgm_options.hpp"

#include <cstdio>
#include <stdexcept>

namespace lidar_sgm {
namespace apps {

const std::set<std::string>& sgmValueOptions() {
  static const std::set<std::string> options{"alpha", "alpha_mode", "sigma", "lidar_cost_cap", "num_disparities", "min_disparity",
                                             "paths", "p1", "p2", "uniqueness", "lr_max_diff", "median", "census",
                                             "backend", "lidar_coverage_rows", "scale", "threads"};
  return options;
}

const std::set<std::string>& sgmFlagOptions() {
  static const std::set<std::string> flags{"no_lr_check", "lr_check_with_lidar", "stereo_cost_without_lidar"};
  return flags;
}

std::string sgmOptionsHelp() {
  const Parameters d;
  char text[4000];
  std::snprintf(text, sizeof(text),
                "  -alpha A                 LiDAR weight of the fused cost, in [0, 1] (default: %g)\n"
                "  -alpha_mode fixed|adaptive  fixed: alpha at every pixel; adaptive: more LiDAR weight within 8 px of\n"
                "                           a LiDAR point and in a dense scan, alpha far from a sparse one (default: %s)\n"
                "  -sigma S                 LiDAR disparity std-dev [px] (default: %g)\n"
                "  -lidar_cost_cap C        upper bound of the LiDAR cost, in [1, 255] (default: %d)\n"
                "  -num_disparities N       disparity search range, multiple of 16 (default: %d)\n"
                "  -min_disparity M         smallest disparity (default: %d)\n"
                "  -paths 4|8               SGM aggregation paths (default: %d)\n"
                "  -p1 P1                   small-jump penalty (default: %d)\n"
                "  -p2 P2                   large-jump penalty, > P1 (default: %d)\n"
                "  -uniqueness U            uniqueness ratio [%%], 0 = off (default: %d)\n"
                "  -no_lr_check             skip the left-right consistency check (default: on in stereo-only mode)\n"
                "  -lr_check_with_lidar     also check in fused mode (default: off; fewer outliers, lower density)\n"
                "  -lr_max_diff D           largest left-right difference [px] (default: %d)\n"
                "  -median 0|3|5            median filter size, 0 = off (default: %d)\n"
                "  -census 9x7|cs9x7        census window: full or centre-symmetric (default: 9x7)\n"
                "  -stereo_cost_without_lidar  full C_S where no LiDAR point is (default: the paper's (1-alpha)*C_S)\n"
                "  -lidar_coverage_rows R   fused LR check spares pixels with a LiDAR point within +-R rows (default: %d)\n"
                "  -scale 1|0.5             match at full or half resolution (0.5: the paper's fast mode; needs\n"
                "                           -num_disparities a multiple of 32 and an even -min_disparity; the\n"
                "                           disparity and cloud keep the full size) (default: %g)\n"
                "  -threads N               matcher threads, 0 = all hardware threads; never changes the result\n"
                "                           (default: %d)\n"
                "  -backend NAME            auto, cpu_ref, cpu or cuda (default: auto, the fastest built)\n",
                d.alpha, toString(d.alphaMode).c_str(), d.sigma, d.lidarCostCap, d.numDisparities, d.minDisparity, d.paths, d.P1, d.P2,
                d.uniquenessRatio, d.disp12MaxDiff, d.medianSize, d.lidarCoverageRows, d.scale, d.threads);
  return text;
}

Parameters parametersFrom(const Arguments& args) {
  Parameters p;
  p.alpha = static_cast<float>(args.number("alpha", p.alpha));
  const std::string alphaMode = args.text("alpha_mode", toString(p.alphaMode));
  try {
    p.alphaMode = alphaModeFromString(alphaMode);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("option -alpha_mode: '" + alphaMode + "' must be fixed or adaptive");
  }
  p.sigma = static_cast<float>(args.number("sigma", p.sigma));
  p.lidarCostCap = args.integer("lidar_cost_cap", p.lidarCostCap);
  p.numDisparities = args.integer("num_disparities", p.numDisparities);
  p.minDisparity = args.integer("min_disparity", p.minDisparity);
  p.paths = args.integer("paths", p.paths);
  p.P1 = args.integer("p1", p.P1);
  p.P2 = args.integer("p2", p.P2);
  p.uniquenessRatio = args.integer("uniqueness", p.uniquenessRatio);
  p.lrCheck = !args.has("no_lr_check");
  p.lrCheckWithLidar = args.has("lr_check_with_lidar");
  p.disp12MaxDiff = args.integer("lr_max_diff", p.disp12MaxDiff);
  p.medianSize = args.integer("median", p.medianSize);
  p.stereoCostWithoutLidar = args.has("stereo_cost_without_lidar");
  p.lidarCoverageRows = args.integer("lidar_coverage_rows", p.lidarCoverageRows);
  p.scale = static_cast<float>(args.number("scale", p.scale));
  p.threads = args.integer("threads", p.threads);
  const std::string census = args.text("census", "9x7");
  if (census == "9x7") {
    p.censusType = CensusType::Census9x7;
  } else if (census == "cs9x7") {
    p.censusType = CensusType::CenterSymmetric9x7;
  } else {
    throw std::invalid_argument("option -census: '" + census + "' must be 9x7 or cs9x7");
  }
  validate(p);
  return p;
}

Backend backendFrom(const Arguments& args) {
  const std::string name = args.text("backend", "auto");
  Backend backend = Backend::Auto;
  try {
    backend = backendFromString(name);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -backend: ") + e.what());
  }
  if (!isAvailable(backend)) {
    std::string built;
    for (Backend b : {Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
      if (isAvailable(b)) built += ", " + toString(b);
    }
    throw std::invalid_argument("option -backend: " + name + " is not built into this library (available: auto" +
                                built + ")");
  }
  return backend;
}

std::set<std::string> joined(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

}  // namespace apps
}  // namespace lidar_sgm
