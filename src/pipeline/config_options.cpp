#include "lidar_sgm/pipeline/config_options.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "lidar_sgm/core/confidence.hpp"

namespace lidar_sgm {
namespace {

[[noreturn]] void fail(const char* name, const std::string& what) {
  throw std::invalid_argument(std::string("option -") + name + ": " + what);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

bool flagValue(const char* name, const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  fail(name, "a flag is true or false, not '" + text + "'");
}

std::string flagText(bool given) { return given ? "true" : "false"; }

constexpr const char* kNoValue = "";  // a flag takes no value; its help says what happens without it

// The table. Every entry reads and writes one setting of DensifierConfig; its default is the
// struct's. The help follows the paper's terms (Eq. 1 penalties, Eq. 4 sigma, Eq. 5 alpha).
std::vector<DensifierOption> makeTable() {
  const DensifierConfig d;
  const geometry::DisparityRangeRule& rule = d.rangeRule;
  const geometry::OcclusionFilter& occlusion = d.projection.occlusion;
  const SkyFilterOptions& sky = d.filters.sky;
  const OutlierFilterOptions& outliers = d.filters.outliers;
  using G = OptionGroup;
  using S = OptionScope;
  using K = OptionKind;
  using C = DensifierConfig;
  std::vector<DensifierOption> t;
  // ---- the method ----
  t.push_back({"alpha", K::Number, "A", G::Method, S::Disparity,
               "LiDAR weight of the fused cost (Eq. 5), in [0, 1]",
               [](C& c, const std::string& s) { c.matcher.alpha = static_cast<float>(parseOptionNumber("alpha", s)); },
               [](const C& c) { return number(c.matcher.alpha); }});
  t.push_back({"alpha_mode", K::Choice, "fixed|adaptive", G::Method, S::Disparity,
               "fixed: alpha at every pixel; adaptive: more LiDAR weight within 8 px of a LiDAR point and in a "
               "dense scan, alpha far from a sparse one",
               [](C& c, const std::string& s) {
                 if (s != "fixed" && s != "adaptive") fail("alpha_mode", "'" + s + "' must be fixed or adaptive");
                 c.matcher.alphaMode = alphaModeFromString(s);
               },
               [](const C& c) { return toString(c.matcher.alphaMode); }});
  t.push_back({"sigma", K::Number, "S", G::Method, S::Disparity, "LiDAR disparity std-dev [px] (Eq. 4)",
               [](C& c, const std::string& s) { c.matcher.sigma = static_cast<float>(parseOptionNumber("sigma", s)); },
               [](const C& c) { return number(c.matcher.sigma); }});
  t.push_back({"lidar_cost_cap", K::Integer, "C", G::Method, S::Disparity,
               "upper bound of the LiDAR cost (Eq. 4), in [1, 255]",
               [](C& c, const std::string& s) { c.matcher.lidarCostCap = parseOptionInteger("lidar_cost_cap", s); },
               [](const C& c) { return std::to_string(c.matcher.lidarCostCap); }});
  t.push_back({"disparity_range", K::Choice, "lidar|fixed", G::Method, S::Disparity,
               "where the search range comes from: lidar: from each frame's LiDAR, [0, dmax + max(" +
                   number(rule.marginPx) + " px, " + number(100.0 * rule.marginFraction) +
                   " %)) rounded up to 16 (32 at -scale 0.5), at most " + std::to_string(rule.maxNumDisparities) +
                   ", dmax its largest disparity but " + std::to_string(rule.ignoredPoints) +
                   " strays; a frame without LiDAR gets the fixed one; -num_disparities or -min_disparity alone "
                   "mean fixed",
               [](C& c, const std::string& s) {
                 if (s != "lidar" && s != "fixed") fail("disparity_range", "'" + s + "' must be lidar or fixed");
                 c.rangeMode = s == "fixed" ? DisparityRangeMode::Fixed : DisparityRangeMode::FromLidar;
               },
               [](const C& c) { return toString(c.rangeMode); }});
  t.push_back({"num_disparities", K::Integer, "N", G::Method, S::Disparity,
               "fixed search range (the paper's), a multiple of 16",
               [](C& c, const std::string& s) { c.matcher.numDisparities = parseOptionInteger("num_disparities", s); },
               [](const C& c) { return std::to_string(c.matcher.numDisparities); }});
  t.push_back({"min_disparity", K::Integer, "M", G::Method, S::Disparity, "fixed smallest disparity",
               [](C& c, const std::string& s) { c.matcher.minDisparity = parseOptionInteger("min_disparity", s); },
               [](const C& c) { return std::to_string(c.matcher.minDisparity); }});
  t.push_back({"paths", K::Integer, "4|8", G::Method, S::Disparity, "SGM aggregation paths",
               [](C& c, const std::string& s) { c.matcher.paths = parseOptionInteger("paths", s); },
               [](const C& c) { return std::to_string(c.matcher.paths); }});
  t.push_back({"p1", K::Integer, "P1", G::Method, S::Disparity, "small-jump penalty (Eq. 1)",
               [](C& c, const std::string& s) { c.matcher.P1 = parseOptionInteger("p1", s); },
               [](const C& c) { return std::to_string(c.matcher.P1); }});
  t.push_back({"p2", K::Integer, "P2", G::Method, S::Disparity, "large-jump penalty (Eq. 1), > P1",
               [](C& c, const std::string& s) { c.matcher.P2 = parseOptionInteger("p2", s); },
               [](const C& c) { return std::to_string(c.matcher.P2); }});
  t.push_back({"uniqueness", K::Integer, "U", G::Method, S::Disparity, "uniqueness ratio [%], 0 = off",
               [](C& c, const std::string& s) { c.matcher.uniquenessRatio = parseOptionInteger("uniqueness", s); },
               [](const C& c) { return std::to_string(c.matcher.uniquenessRatio); }});
  t.push_back({"no_lr_check", K::Flag, kNoValue, G::Method, S::Disparity,
               "skip the left-right consistency check (default: on in stereo-only mode)",
               [](C& c, const std::string& s) { c.matcher.lrCheck = !flagValue("no_lr_check", s); },
               [](const C& c) { return flagText(!c.matcher.lrCheck); }});
  t.push_back({"lr_check_with_lidar", K::Flag, kNoValue, G::Method, S::Disparity,
               "also check in fused mode (default: off; fewer outliers, lower density)",
               [](C& c, const std::string& s) { c.matcher.lrCheckWithLidar = flagValue("lr_check_with_lidar", s); },
               [](const C& c) { return flagText(c.matcher.lrCheckWithLidar); }});
  t.push_back({"lr_max_diff", K::Integer, "D", G::Method, S::Disparity, "largest left-right difference [px]",
               [](C& c, const std::string& s) { c.matcher.disp12MaxDiff = parseOptionInteger("lr_max_diff", s); },
               [](const C& c) { return std::to_string(c.matcher.disp12MaxDiff); }});
  t.push_back({"median", K::Integer, "0|3|5", G::Method, S::Disparity, "median filter size, 0 = off",
               [](C& c, const std::string& s) { c.matcher.medianSize = parseOptionInteger("median", s); },
               [](const C& c) { return std::to_string(c.matcher.medianSize); }});
  t.push_back({"census", K::Choice, "9x7|cs9x7", G::Method, S::Disparity,
               "census window: full or centre-symmetric",
               [](C& c, const std::string& s) {
                 if (s == "9x7") {
                   c.matcher.censusType = CensusType::Census9x7;
                 } else if (s == "cs9x7") {
                   c.matcher.censusType = CensusType::CenterSymmetric9x7;
                 } else {
                   fail("census", "'" + s + "' must be 9x7 or cs9x7");
                 }
               },
               [](const C& c) { return std::string(c.matcher.censusType == CensusType::Census9x7 ? "9x7" : "cs9x7"); }});
  t.push_back({"stereo_cost_without_lidar", K::Flag, kNoValue, G::Method, S::Disparity,
               "full C_S where no LiDAR point is (default: the paper's (1-alpha)*C_S)",
               [](C& c, const std::string& s) {
                 c.matcher.stereoCostWithoutLidar = flagValue("stereo_cost_without_lidar", s);
               },
               [](const C& c) { return flagText(c.matcher.stereoCostWithoutLidar); }});
  t.push_back({"lidar_coverage_rows", K::Integer, "R", G::Method, S::Disparity,
               "the fused left-right check spares pixels with a LiDAR point within +-R rows; LiDAR-only: the "
               "crop keeps R rows beyond the scan",
               [](C& c, const std::string& s) {
                 c.matcher.lidarCoverageRows = parseOptionInteger("lidar_coverage_rows", s);
               },
               [](const C& c) { return std::to_string(c.matcher.lidarCoverageRows); }});
  t.push_back({"no_gated_search", K::Flag, kNoValue, G::Method, S::Disparity,
               "search the whole disparity range at every pixel; by default a fused frame searches each pixel's "
               "disparities only around the LiDAR points within +-1 column and +-gated_search_rows rows (min - "
               "margin .. max + margin, widened to a multiple of 16), the whole range elsewhere",
               [](C& c, const std::string& s) { c.matcher.gatedSearch = !flagValue("no_gated_search", s); },
               [](const C& c) { return flagText(!c.matcher.gatedSearch); }});
  t.push_back({"gated_search_margin", K::Integer, "M", G::Method, S::Disparity,
               "the gated search: the window's widening beyond the LiDAR disparities on each side [px], in [0, 512]",
               [](C& c, const std::string& s) {
                 c.matcher.gatedSearchMargin = parseOptionInteger("gated_search_margin", s);
               },
               [](const C& c) { return std::to_string(c.matcher.gatedSearchMargin); }});
  t.push_back({"gated_search_rows", K::Integer, "R", G::Method, S::Disparity,
               "the gated search: a pixel is gated by the LiDAR points within +-R rows (and +-1 column), in [0, 64]",
               [](C& c, const std::string& s) { c.matcher.gatedSearchRows = parseOptionInteger("gated_search_rows", s); },
               [](const C& c) { return std::to_string(c.matcher.gatedSearchRows); }});
  // ---- speed ----
  t.push_back({"scale", K::Number, "1|0.5", G::Speed, S::Disparity,
               "match at full or half resolution (0.5: the paper's fast mode; needs -num_disparities a multiple "
               "of 32 and an even -min_disparity; the disparity and cloud keep the full size)",
               [](C& c, const std::string& s) { c.matcher.scale = static_cast<float>(parseOptionNumber("scale", s)); },
               [](const C& c) { return number(c.matcher.scale); }});
  t.push_back({"threads", K::Integer, "N", G::Speed, S::Disparity,
               "matcher threads, 0 = all hardware threads; never changes the result",
               [](C& c, const std::string& s) { c.matcher.threads = parseOptionInteger("threads", s); },
               [](const C& c) { return std::to_string(c.matcher.threads); }});
  t.push_back({"backend", K::Choice, "NAME", G::Speed, S::Disparity,
               "auto, cpu_ref, cpu or cuda (auto: the fastest built that can run here)",
               [](C& c, const std::string& s) {
                 Backend backend = Backend::Auto;
                 try {
                   backend = backendFromString(s);
                 } catch (const std::invalid_argument& e) {
                   fail("backend", e.what());
                 }
                 if (!isAvailable(backend)) {
                   std::string built;
                   for (Backend b : {Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
                     if (isAvailable(b)) built += ", " + toString(b);
                   }
                   // Not built, or built but unable to run here (cuda without a device): say which.
                   fail("backend", s + " cannot run here: " + unavailableReason(backend) + " (available: auto" + built +
                                       ")");
                 }
                 c.backend = backend;
               },
               [](const C& c) { return toString(c.backend); }});
  t.push_back({"no_confidence", K::Flag, kNoValue, G::Speed, S::Disparity,
               "compute no confidence (faster; no confidence field, -min_confidence 0)",
               [](C& c, const std::string& s) { c.matcher.confidence = !flagValue("no_confidence", s); },
               [](const C& c) { return flagText(!c.matcher.confidence); }});
  // ---- filters ----
  t.push_back({"min_confidence", K::Number, "C", G::Filters, S::Disparity,
               "drop pixels (and points) whose confidence, about the probability that the disparity is right, "
               "is below C in [0, 1]; 0 keeps every pixel",
               [](C& c, const std::string& s) {
                 c.minConfidence = parseOptionNumber("min_confidence", s);
                 if (!(c.minConfidence >= 0.0 && c.minConfidence <= 1.0)) fail("min_confidence", s + " must be in [0, 1]");
               },
               [](const C& c) { return number(c.minConfidence); }});
  t.push_back({"no_occlusion_filter", K::Flag, kNoValue, G::Filters, S::Cloud,
               "keep LiDAR points hidden from the camera (default: drop a point with points more than max(" +
                   number(occlusion.minGap) + " px, " + number(occlusion.relativeGap) +
                   "*d) nearer on two opposite sides within +-" + std::to_string(occlusion.halfWidth) +
                   " columns, +-" + std::to_string(occlusion.halfHeight) + " rows)",
               [](C& c, const std::string& s) {
                 c.projection.occlusion.enabled = !flagValue("no_occlusion_filter", s);
               },
               [](const C& c) { return flagText(!c.projection.occlusion.enabled); }});
  t.push_back({"no_crop_to_scan", K::Flag, kNoValue, G::Filters, S::Disparity,
               "LiDAR-only: keep pixels above the scan's top / below its bottom beam (default: cleared, nothing "
               "was measured there)",
               [](C& c, const std::string& s) { c.cropToScan = !flagValue("no_crop_to_scan", s); },
               [](const C& c) { return flagText(!c.cropToScan); }});
  t.push_back({"no_sky_filter", K::Flag, kNoValue, G::Filters, S::Disparity,
               "keep the sky: pixels above the scan's top return, in a bright (>= " +
                   std::to_string(sky.brightLevel) +
                   ") blank patch of the left image connected to its top row (default: removed, with LiDAR)",
               [](C& c, const std::string& s) { c.filters.sky.enabled = !flagValue("no_sky_filter", s); },
               [](const C& c) { return flagText(!c.filters.sky.enabled); }});
  const std::string window = std::to_string(2 * sky.textureRadius + 1);
  t.push_back({"sky_texture", K::Number, "T", G::Filters, S::Disparity,
               "blank = mean |gradient| of the left image below T levels/px in a " + window + "x" + window + " window",
               [](C& c, const std::string& s) { c.filters.sky.textureThreshold = parseOptionNumber("sky_texture", s); },
               [](const C& c) { return number(c.filters.sky.textureThreshold); }});
  t.push_back({"no_outlier_filter", K::Flag, kNoValue, G::Filters, S::Disparity,
               "keep isolated and flying points (default: removed, with LiDAR)",
               [](C& c, const std::string& s) { c.filters.outliers.enabled = !flagValue("no_outlier_filter", s); },
               [](const C& c) { return flagText(!c.filters.outliers.enabled); }});
  t.push_back({"outlier_min_neighbours", K::Integer, "N", G::Filters, S::Disparity,
               "a point needs N of its " +
                   std::to_string((2 * outliers.radius + 1) * (2 * outliers.radius + 1) - 1) + " neighbours within " +
                   number(100.0 * outliers.relativeTolerance) + " % of its disparity (at least " +
                   number(outliers.minTolerance) + " px), 0 = off",
               [](C& c, const std::string& s) {
                 c.filters.outliers.minNeighbours = parseOptionInteger("outlier_min_neighbours", s);
               },
               [](const C& c) { return std::to_string(c.filters.outliers.minNeighbours); }});
  t.push_back({"no_hidden_lidar_filter", K::Flag, kNoValue, G::Filters, S::Disparity,
               "fused: keep in the matching the LiDAR points a stereo-only match sees a nearer surface in front of "
               "(object edges the LiDAR sees past, glass, moved cars) (default: left out)",
               [](C& c, const std::string& s) { c.hiddenLidar.enabled = !flagValue("no_hidden_lidar_filter", s); },
               [](const C& c) { return flagText(!c.hiddenLidar.enabled); }});
  t.push_back({"hidden_lidar_gap", K::Number, "PX", G::Filters, S::Disparity,
               "a LiDAR point is hidden where the stereo disparity is larger by more than PX and " +
                   number(100.0 * d.hiddenLidar.relativeGap) + " % of its own, in [0.5, 64]",
               [](C& c, const std::string& s) { c.hiddenLidar.minGap = parseOptionNumber("hidden_lidar_gap", s); },
               [](const C& c) { return number(c.hiddenLidar.minGap); }});
  t.push_back({"hidden_lidar_scale", K::Number, "S", G::Filters, S::Disparity,
               "the stereo witness of the hidden-LiDAR filter matched at S times the frame's scale: 0.5 (an eighth "
               "of the frame's work), 0.25 (a sixty-fourth, a little less exact) or 1 (the frame's own, a little "
               "more exact); only on the rows the LiDAR points span",
               [](C& c, const std::string& s) {
                 c.hiddenLidar.witnessScale = static_cast<float>(parseOptionNumber("hidden_lidar_scale", s));
               },
               [](const C& c) { return number(c.hiddenLidar.witnessScale); }});
  t.push_back({"no_lidar_anchor", K::Flag, kNoValue, G::Filters, S::Disparity,
               "with LiDAR: keep the matcher's own sub-pixel disparity in the far scene (default: each pixel at most " +
                   number(d.lidarAnchor.maxDisparity) +
                   " px takes the mean offset of the LiDAR points on its surface within +-" +
                   std::to_string(d.lidarAnchor.halfWidth) + " columns, +-" + std::to_string(d.lidarAnchor.halfHeight) +
                   " rows)",
               [](C& c, const std::string& s) { c.lidarAnchor.enabled = !flagValue("no_lidar_anchor", s); },
               [](const C& c) { return flagText(!c.lidarAnchor.enabled); }});
  t.push_back({"lidar_anchor_max_disparity", K::Number, "PX", G::Filters, S::Disparity,
               "the LiDAR anchors the sub-pixel disparity of pixels at most PX px (the far scene; KITTI: 20 px is "
               "~19 m), in [0, 1024]",
               [](C& c, const std::string& s) {
                 c.lidarAnchor.maxDisparity = parseOptionNumber("lidar_anchor_max_disparity", s);
               },
               [](const C& c) { return number(c.lidarAnchor.maxDisparity); }});
  t.push_back({"lidar_consistency", K::Flag, kNoValue, G::Filters, S::Disparity,
               "fused: leave out of the matching the LiDAR points the stereo pair contradicts (moving objects, glass; "
               "KITTI142: foreground error 9.1 -> 6.6 %, but P1-P3 lose 0.2-0.4 points) (default: off)",
               [](C& c, const std::string& s) { c.lidarConsistency.enabled = flagValue("lidar_consistency", s); },
               [](const C& c) { return flagText(c.lidarConsistency.enabled); }});
  t.push_back({"lidar_consistency_ratio", K::Number, "R", G::Filters, S::Disparity,
               "a LiDAR point is contradicted where the pair matches R times better (7x7 zero-mean SAD) more than " +
                   number(d.lidarConsistency.minDisagreement) + " px away from its disparity, in [1, 100]",
               [](C& c, const std::string& s) {
                 c.lidarConsistency.costRatio = parseOptionNumber("lidar_consistency_ratio", s);
               },
               [](const C& c) { return number(c.lidarConsistency.costRatio); }});
  t.push_back({"no_pair_check", K::Flag, kNoValue, G::Filters, S::Disparity,
               "match a pair that looks swapped (default: refused when the LiDAR, or without it most matches, "
               "find the right image on the wrong side)",
               [](C& c, const std::string& s) { c.pairCheck = !flagValue("no_pair_check", s); },
               [](const C& c) { return flagText(!c.pairCheck); }});
  // ---- the cloud ----
  t.push_back({"keep_organized", K::Flag, kNoValue, G::Output, S::Cloud,
               "one point per pixel, NaN where there is none (default: valid points only)",
               [](C& c, const std::string& s) { c.reprojection.keepOrganized = flagValue("keep_organized", s); },
               [](const C& c) { return flagText(c.reprojection.keepOrganized); }});
  t.push_back({"frame", K::Choice, "lidar|camera", G::Output, S::Cloud,
               "the points' frame: lidar (the input's) or camera (the rectified left camera)",
               [](C& c, const std::string& s) {
                 if (s != "lidar" && s != "camera") fail("frame", "'" + s + "' must be lidar or camera");
                 c.reprojection.frame = s == "camera" ? geometry::OutputFrame::Camera : geometry::OutputFrame::Lidar;
               },
               [](const C& c) {
                 return std::string(c.reprojection.frame == geometry::OutputFrame::Camera ? "camera" : "lidar");
               }});
  t.push_back({"max_depth", K::Number, "M", G::Output, S::Cloud,
               "drop points (and depth) deeper than M metres, 0 = keep all",
               [](C& c, const std::string& s) {
                 const double m = parseOptionNumber("max_depth", s);
                 if (m < 0.0) fail("max_depth", "must be >= 0 [m] (0 = keep all)");
                 c.reprojection.maxDepth = m == 0.0 ? std::numeric_limits<double>::infinity() : m;
               },
               [](const C& c) { return std::isinf(c.reprojection.maxDepth) ? "0" : number(c.reprojection.maxDepth); }});
  t.push_back({"stride", K::Integer, "S", G::Output, S::Cloud, "every S-th pixel in x and y",
               [](C& c, const std::string& s) {
                 c.reprojection.stride = parseOptionInteger("stride", s);
                 if (c.reprojection.stride < 1) fail("stride", "must be >= 1");
               },
               [](const C& c) { return std::to_string(c.reprojection.stride); }});
  return t;
}

// "  -name VALUE" in a 27-column field, then the words of `text` wrapped at 112 columns under
// column 27; `last` (the default) is one word, so that a reader finds "(default: X)" whole.
std::string helpLines(const std::string& head, const std::string& text, const std::string& last) {
  constexpr std::size_t kColumn = 27;
  constexpr std::size_t kWidth = 112;
  std::vector<std::string> words;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t next = text.find(' ', pos);
    if (next == std::string::npos) next = text.size();
    if (next > pos) words.push_back(text.substr(pos, next - pos));
    pos = next + 1;
  }
  if (!last.empty()) words.push_back(last);
  std::string out = head;
  if (out.size() + 2 > kColumn) {
    out += "  ";
  } else {
    out.resize(kColumn, ' ');
  }
  std::size_t lineStart = 0;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0 && out.size() - lineStart + 1 + words[i].size() > kWidth) {
      out += "\n";
      lineStart = out.size();
      out.append(kColumn, ' ');
    } else if (i > 0) {
      out += ' ';
    }
    out += words[i];
  }
  return out + "\n";
}

}  // namespace

const std::vector<DensifierOption>& densifierOptions() {
  static const std::vector<DensifierOption> table = makeTable();
  return table;
}

std::vector<const DensifierOption*> densifierOptions(OptionScope scope) {
  std::vector<const DensifierOption*> options;
  for (const DensifierOption& o : densifierOptions()) {
    if (scope == OptionScope::Cloud || o.scope == OptionScope::Disparity) options.push_back(&o);
  }
  return options;
}

const DensifierOption* findDensifierOption(const std::string& name) {
  for (const DensifierOption& o : densifierOptions()) {
    if (name == o.name) return &o;
  }
  return nullptr;
}

std::string defaultValue(const DensifierOption& option) { return option.value(DensifierConfig()); }

DensifierConfig configFromOptions(const std::map<std::string, std::string>& values, const std::set<std::string>& flags,
                                  const DensifierConfig& base) {
  for (const auto& [name, text] : values) {
    const DensifierOption* o = findDensifierOption(name);
    if (o == nullptr || o->kind == OptionKind::Flag) throw std::invalid_argument("unknown option -" + name);
  }
  for (const std::string& name : flags) {
    const DensifierOption* o = findDensifierOption(name);
    if (o == nullptr || o->kind != OptionKind::Flag) throw std::invalid_argument("unknown flag -" + name);
  }
  DensifierConfig config = base;
  for (const DensifierOption& o : densifierOptions()) {
    if (o.kind == OptionKind::Flag) {
      if (flags.count(o.name) > 0) o.apply(config, "true");
    } else if (const auto it = values.find(o.name); it != values.end()) {
      o.apply(config, it->second);
    }
  }
  // A range given by hand is meant to be searched; the confidence's absence means no minimum.
  if ((values.count("num_disparities") > 0 || values.count("min_disparity") > 0) &&
      values.count("disparity_range") == 0) {
    config.rangeMode = DisparityRangeMode::Fixed;
  }
  if (flags.count("no_confidence") > 0) {
    if (values.count("min_confidence") == 0) {
      config.minConfidence = 0.0;
    } else if (config.minConfidence > 0.0) {
      throw std::invalid_argument("option -min_confidence: needs the confidence, which -no_confidence turns off");
    }
  }
  validate(config);
  return config;
}

std::string optionsHelp(OptionGroup group, OptionScope scope) {
  std::string help;
  for (const DensifierOption* o : densifierOptions(scope)) {
    if (o->group != group) continue;
    std::string head = std::string("  -") + o->name;
    if (o->kind != OptionKind::Flag) head += std::string(" ") + o->valueName;
    help += helpLines(head, o->help, o->kind == OptionKind::Flag ? "" : "(default: " + defaultValue(*o) + ")");
  }
  return help;
}

}  // namespace lidar_sgm
