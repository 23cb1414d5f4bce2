#include "common/sgm_options.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "lidar_sgm/core/confidence.hpp"

namespace lidar_sgm {
namespace apps {

const std::set<std::string>& sgmValueOptions() {
  static const std::set<std::string> options{"alpha", "alpha_mode", "sigma", "lidar_cost_cap", "num_disparities", "min_disparity",
                                             "paths", "p1", "p2", "uniqueness", "lr_max_diff", "median", "census",
                                             "backend", "lidar_coverage_rows", "scale", "threads",
                                             "min_confidence", "disparity_range"};
  return options;
}

const std::set<std::string>& sgmFlagOptions() {
  static const std::set<std::string> flags{"no_lr_check", "lr_check_with_lidar", "stereo_cost_without_lidar",
                                           "no_confidence"};
  return flags;
}

std::string sgmMethodHelp() {
  const Parameters d;
  char text[4400];
  std::snprintf(text, sizeof(text),
                "  -alpha A                 LiDAR weight of the fused cost, in [0, 1] (default: %g)\n"
                "  -alpha_mode fixed|adaptive  fixed: alpha at every pixel; adaptive: more LiDAR weight within 8 px of\n"
                "                           a LiDAR point and in a dense scan, alpha far from a sparse one (default: %s)\n"
                "  -sigma S                 LiDAR disparity std-dev [px] (default: %g)\n"
                "  -lidar_cost_cap C        upper bound of the LiDAR cost, in [1, 255] (default: %d)\n"
                "  -disparity_range lidar|fixed  where the search range comes from (default: lidar: from each\n"
                "                           frame's LiDAR, [0, dmax + max(8 px, 5 %%)) rounded up to 16 (32 at\n"
                "                           -scale 0.5), at most 256, dmax its largest disparity but 10 strays;\n"
                "                           a frame without LiDAR gets the fixed one); -num_disparities or\n"
                "                           -min_disparity alone mean fixed\n"
                "  -num_disparities N       fixed search range (the paper's), multiple of 16 (default: %d)\n"
                "  -min_disparity M         fixed smallest disparity (default: %d)\n"
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
                "  -lidar_coverage_rows R   fused LR check spares pixels with a LiDAR point within +-R rows (default: %d)\n",
                d.alpha, toString(d.alphaMode).c_str(), d.sigma, d.lidarCostCap, d.numDisparities, d.minDisparity, d.paths, d.P1, d.P2,
                d.uniquenessRatio, d.disp12MaxDiff, d.medianSize, d.lidarCoverageRows);
  return text;
}

std::string sgmSpeedHelp() {
  const Parameters d;
  char text[1200];
  std::snprintf(text, sizeof(text),
                "  -scale 1|0.5             match at full or half resolution (0.5: the paper's fast mode; needs\n"
                "                           -num_disparities a multiple of 32 and an even -min_disparity; the\n"
                "                           disparity and cloud keep the full size) (default: %g)\n"
                "  -threads N               matcher threads, 0 = all hardware threads; never changes the result\n"
                "                           (default: %d)\n"
                "  -backend NAME            auto, cpu_ref, cpu or cuda (default: auto, the fastest built)\n"
                "  -no_confidence           compute no confidence (faster; no confidence field, -min_confidence 0)\n",
                d.scale, d.threads);
  return text;
}

std::string sgmConfidenceHelp() {
  char text[600];
  std::snprintf(text, sizeof(text),
                "  -min_confidence C        drop pixels (and points) whose confidence, about the probability that\n"
                "                           the disparity is right, is below C in [0, 1]; 0 keeps every pixel\n"
                "                           (default: %g)\n",
                kDefaultMinConfidence);
  return text;
}

std::string sgmOptionsHelp() { return sgmMethodHelp() + sgmSpeedHelp() + sgmConfidenceHelp(); }

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
  p.confidence = !args.has("no_confidence");
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

bool fixedDisparityRange(const Arguments& args) {
  const bool explicitRange = args.has("num_disparities") || args.has("min_disparity");
  const std::string mode = args.text("disparity_range", explicitRange ? "fixed" : "lidar");
  if (mode != "lidar" && mode != "fixed") {
    throw std::invalid_argument("option -disparity_range: '" + mode + "' must be lidar or fixed");
  }
  return mode == "fixed";
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
    // Not built, or built but unable to run here (cuda without a device): say which.
    throw std::invalid_argument("option -backend: " + name + " cannot run here: " + unavailableReason(backend) +
                                " (available: auto" + built + ")");
  }
  return backend;
}

std::set<std::string> joined(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

double minConfidenceFrom(const Arguments& args) {
  if (args.has("no_confidence")) {
    if (args.has("min_confidence") && args.number("min_confidence", 0.0) > 0.0) {
      throw std::invalid_argument("option -min_confidence: needs the confidence, which -no_confidence turns off");
    }
    return 0.0;
  }
  const double c = args.number("min_confidence", kDefaultMinConfidence);
  if (!(c >= 0.0 && c <= 1.0)) {
    throw std::invalid_argument("option -min_confidence: " + std::to_string(c) + " must be in [0, 1]");
  }
  return c;
}

}  // namespace apps
}  // namespace lidar_sgm
