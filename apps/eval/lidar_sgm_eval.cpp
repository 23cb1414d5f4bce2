// lidar_sgm_eval: the evaluation protocols of EVALUATION.md (P1: GT frames with simulated LiDAR,
// P2: real LiDAR with every 4th ring held out, P3: the project's synthetic scenes), every method
// side by side, an alpha sweep per group of frames, pictures, markdown tables and a JSON file.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cloud_score.hpp"
#include "common/arguments.hpp"
#include "common/config_arguments.hpp"
#include "common/help_layout.hpp"
#include "common/help_version.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/cloud_distance_report.hpp"
#include "lidar_sgm/eval/confidence_fit.hpp"
#include "lidar_sgm/eval/confidence_report.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/eval/groups.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/eval/report.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/version.hpp"

namespace fs = std::filesystem;
using namespace lidar_sgm;
using namespace lidar_sgm::eval;

namespace {

void printHelp(const char* program) {
  char usage[900];
  std::snprintf(usage, sizeof(usage),
                "Syntax is: %s -out DIR [options]\n"
                "       or: %s -cloud CLOUD -reference REFERENCE [-tau T] [-bands E,E,...] [-out DIR]\n"
                "Runs the evaluation protocols of docs/EVALUATION.md (P1: KITTI 2015 with simulated LiDAR, P2: real\n"
                "KITTI LiDAR, KITTI142: the paper's own, P3: synthetic frames) and writes tables, plots, pictures\n"
                "and JSON. The whole plan\n"
                "takes minutes (BENCHMARK.md); it is printed before anything runs. With -cloud, it scores one\n"
                "cloud against a reference cloud in 3D instead (below).\n",
                program, program);
  const std::string inputs =
      "  -data ROOT         third-party data root (default: $LIDAR_SGM_DATA, else ../shared/data, relative to\n"
      "                     the working directory)\n"
      "  -protocols LIST    comma-separated subset of P1,P2,KITTI142,P3 (default: all four; KITTI142 is the\n"
      "                     paper's own: KITTI 2015 frames with their raw scans, its Tables I and II)\n"
      "  -kitti142_frames N the first N frames of KITTI142 only, 0 = all (default: 0)\n"
      "  -synth_frames N    synthetic frames per P3 set (default: 10, seeds 100..)\n"
      "  -synth_size WxH    synthetic frame size (default: 1242x375)\n"
      "  -p3_sets LIST      comma-separated subset of clear64,rain64,clear128 (default: all three;\n"
      "                     clear64 has the third camera for Triple-SGM)\n";
  const std::string outputs =
      "  -out DIR           output folder, required (the documented run: -out out/eval)\n"
      "  -no_pictures       skip the per-frame pictures\n"
      "  -fit_confidence    instead of the protocols: fit the confidence models on synthetic frames and check\n"
      "                     them on held-out ones (writes DIR/confidence_fit.md and DIR/reliability.png)\n";
  const std::string method =
      "  -alpha_step S      alpha sweep step in (0, 1] (default: 0.1)\n"
      "  -disparity_range lidar|fixed  the LiDAR-SGM methods' search range: from each frame's LiDAR, as the\n"
      "                     tools (default: lidar; the methods without LiDAR keep the fixed one), or fixed\n"
      "  -num_disparities N the fixed range [0, N) on every frame (alone: implies -disparity_range fixed)\n"
      "                     (default: the frame's: 128, or its GT's max + 8 px rounded up to 16 where more)\n"
      "  and every other SGM option of lidar_sgm_disparity (-sigma, -p1, -p2, -no_lr_check, ...) for the\n"
      "  LiDAR-SGM methods\n";
  const std::string speed =
      "  -threads N         threads in all, 0 = all hardware threads (default: 0): frames run in parallel and\n"
      "                     each frame's matcher gets an equal share of the rest; results do not depend on it\n"
      "  -scale 1|0.5       match the LiDAR-SGM methods at full or half resolution (0.5: the paper's fast\n"
      "                     mode; each frame's search range is rounded up to a multiple of 32) (default: 1)\n"
      "  -backend NAME      the LiDAR-SGM methods' backend: auto, cpu_ref, cpu or cuda (default: auto)\n";
  const std::string filters = "  the LiDAR-SGM methods run with these, as the tools:\n" +
                              optionsHelp(OptionGroup::Filters, OptionScope::Disparity);
  const std::vector<apps::HelpExample> examples{
      {"The documented run: every protocol, on the KITTI data in ../shared/data (minutes):",
       "lidar_sgm_eval -out out/eval"},
      {"P3 alone, on small synthetic frames (no third-party data needed), without pictures:",
       "lidar_sgm_eval -out out/p3 -protocols P3 -p3_sets clear64 -synth_frames 2 -synth_size 320x96 "
       "-alpha_step 0.5 -no_pictures"},
      {"P1 at half scale (the paper's fast mode), on the KITTI 2015 frames in ../shared/data:",
       "lidar_sgm_eval -out out/p1_half -protocols P1 -scale 0.5"},
      {"A cloud against a reference in 3D (lidar_sgm_densify's first example's against the sample's scan), "
       "at 10 and 20 cm:",
       "lidar_sgm_eval -cloud dense.pcd -reference data/sample/velodyne/000000.bin -tau 0.1,0.2 -out out/score"},
  };
  const std::string text = apps::helpText(usage,
                                          {{"Inputs", inputs},
                                           {"Outputs", outputs},
                                           {"A cloud against a reference cloud", apps::cloudScoreHelp()},
                                           {"Method", method},
                                           {"Speed", speed},
                                           {"Filters", filters}},
                                          examples);
  std::fputs(text.c_str(), stdout);
}

/// The comma-separated `option`'s items, each checked against `known` (its default).
std::vector<std::string> listOption(const apps::Arguments& args, const std::string& option, const std::string& known) {
  std::vector<std::string> items;
  std::stringstream stream(args.text(option, known));
  for (std::string item; std::getline(stream, item, ',');) {
    if (("," + known + ",").find("," + item + ",") == std::string::npos) {
      throw std::invalid_argument("option -" + option + ": unknown item '" + item + "' (known: " + known + ")");
    }
    items.push_back(item);
  }
  return items;
}

std::string joinedText(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

GroupSelection selectionFrom(const apps::Arguments& args, const std::string& root) {
  GroupSelection selection;
  selection.dataRoot = root;
  selection.protocols = listOption(args, "protocols", "P1,P2,KITTI142,P3");
  selection.kitti142Frames = args.integer("kitti142_frames", 0);
  if (selection.kitti142Frames < 0) throw std::invalid_argument("option -kitti142_frames: must be >= 0 (0 = all)");
  selection.p3Sets = listOption(args, "p3_sets", "clear64,rain64,clear128");
  selection.synthFrames = args.integer("synth_frames", 10);
  const std::string size = args.text("synth_size", "1242x375");
  if (std::sscanf(size.c_str(), "%dx%d", &selection.synthWidth, &selection.synthHeight) != 2) {
    throw std::invalid_argument("option -synth_size: '" + size + "' is not WIDTHxHEIGHT");
  }
  return selection;
}

/// The LiDAR-SGM methods' search range, in words.
std::string rangeText(const GroupRunOptions& run) {
  const std::string fixed =
      run.fixedNumDisparities > 0 ? "[0, " + std::to_string(run.fixedNumDisparities) + ")" : "the frame's";
  if (run.config.rangeMode == DisparityRangeMode::Fixed) return fixed + " (fixed)";
  return "from each frame's LiDAR (without LiDAR: " + fixed + ")";
}

/// Which disparities each pixel searches (Parameters::gatedSearch).
std::string searchText(const Parameters& matcher) {
  if (!matcher.gatedSearch) return "the whole range at every pixel (-no_gated_search)";
  return "LiDAR-gated in fused frames (margin " + std::to_string(matcher.gatedSearchMargin) + " px, +-" +
         std::to_string(matcher.gatedSearchRows) +
         " rows; the whole range where no point is, in LiDAR-only and in stereo-only frames)";
}

/// What the run will do, before it loads anything: it takes minutes, so it never starts unseen.
void printPlan(const GroupSelection& selection, const std::string& out, const GroupRunOptions& run, bool pictures) {
  const auto has = [](const std::vector<std::string>& items, const char* item) {
    return std::find(items.begin(), items.end(), item) != items.end();
  };
  std::vector<std::string> methods;
  for (const Method& m : baseMethods()) methods.push_back(displayName(m));
  std::vector<std::string> sweep;
  for (double a : run.alphas) sweep.push_back(std::to_string(a).substr(0, 4));
  std::printf("lidar_sgm_eval %s: the plan\n", versionString());
  std::printf("  protocols: %s\n", joinedText(selection.protocols, ", ").c_str());
  const char* root = selection.dataRoot.c_str();
  if (has(selection.protocols, "P1")) std::printf("    P1: every GT frame under %s, simulated 64-beam LiDAR\n", root);
  if (has(selection.protocols, "P2")) std::printf("    P2: the real KITTI scans under %s, every 4th ring held out\n", root);
  if (has(selection.protocols, "KITTI142")) {
    std::printf("    KITTI142: %s/kitti2015_lidar, KITTI 2015 frames with their raw scans (%s), the paper's tables\n",
                root, selection.kitti142Frames > 0 ? ("the first " + std::to_string(selection.kitti142Frames)).c_str()
                                                   : "every frame");
  }
  if (has(selection.protocols, "P3")) {
    std::printf("    P3: synthetic sets %s, %d frames each (seeds 100..), %dx%d\n",
                joinedText(selection.p3Sets, ", ").c_str(), selection.synthFrames, selection.synthWidth,
                selection.synthHeight);
  }
  const bool threeCameras = has(selection.protocols, "P3") && has(selection.p3Sets, "clear64");
  std::printf("  methods:   %s; LiDAR-SGM at alpha %s%s\n", joinedText(methods, ", ").c_str(),
              joinedText(sweep, ", ").c_str(), threeCameras ? "; on P3 clear64 also the three-camera methods" : "");
  std::printf("  matcher:   backend %s, scale %g, alpha mode %s, %d threads in all, disparity range %s\n",
              toString(resolve(run.config.backend)).c_str(), run.config.matcher.scale,
              toString(run.config.matcher.alphaMode).c_str(), run.threads, rangeText(run).c_str());
  std::printf("  search:    %s\n", searchText(run.config.matcher).c_str());
  std::printf("  outputs:   %s/results.md, %s/results.json, %s/plots/%s\n", out.c_str(), out.c_str(), out.c_str(),
              pictures ? (", " + out + "/pictures/").c_str() : "");
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  const apps::Arguments args(
      argc, argv,
      apps::joined(apps::joined(apps::configValueOptions(OptionScope::Disparity),
                                {"data", "out", "protocols", "synth_frames", "synth_size", "p3_sets", "alpha_step",
                                 "kitti142_frames"}),
                   apps::cloudScoreOptions()),
      apps::joined(apps::configFlagOptions(OptionScope::Disparity), {"no_pictures", "fit_confidence"}));
  if (apps::answerHelpOrVersion(args, "lidar_sgm_eval", [&] { printHelp(argv[0]); })) return 0;
  if (args.has("cloud") || args.has("reference")) return apps::runCloudScore(args);
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  const std::string root = resolveDataRoot(args.text("data", ""));
  // Required: the run takes minutes and writes a folder, so it never starts by accident.
  const std::string out = args.text("out", "");
  // The configuration of every LiDAR-SGM method, as the tools read it (alpha is the method's;
  // numDisparities the frame's; threads are shared out by runGroup).
  const DensifierConfig config = apps::configFrom(args, OptionScope::Disparity);
  const Parameters& base = config.matcher;
  const Backend backend = config.backend;
  const double step = args.number("alpha_step", 0.1);
  if (!(step > 0.0 && step <= 1.0)) throw std::invalid_argument("option -alpha_step: must be in (0, 1]");
  const int threads = effectiveThreads(base);  // -threads, validated with the SGM options
  GroupRunOptions runOptions;
  runOptions.alphas = sweepAlphas(step);
  runOptions.threads = threads;
  runOptions.config = config;
  // -num_disparities: that fixed range on every frame (e.g. the paper's 128); else the frame's.
  if (args.has("num_disparities")) runOptions.fixedNumDisparities = base.numDisparities;
  if (args.has("min_disparity")) {
    throw std::invalid_argument("option -min_disparity: the evaluation searches from 0 (the frames' GT starts there)");
  }
  if (args.has("fit_confidence")) {
    if (out.empty()) throw std::invalid_argument("option -fit_confidence: -out DIR is required");
    ConfidenceFitOptions fit;
    fit.out = out;
    fit.threads = threads;
    apps::Timer timer;
    std::printf("Fitting the confidence models (3 modes x 2 P3 sets) into %s\n", out.c_str());
    runConfidenceFit(fit);
    std::printf("Results in %s: confidence_fit.md, reliability.png [done, %.0f ms]\n", out.c_str(), timer.elapsedMs());
    return 0;
  }
  const GroupSelection selection = selectionFrom(args, root);
  printPlan(selection, out.empty() ? "DIR" : out, runOptions, !args.has("no_pictures"));
  if (out.empty()) {
    throw std::invalid_argument("nothing run: -out DIR is required, the folder for the results above "
                                "(e.g. -out out/eval; -h for every option)");
  }
  fs::create_directories(out + "/plots");
  const std::string pictures = args.has("no_pictures") ? "" : out + "/pictures";
  if (!pictures.empty()) fs::create_directories(pictures);
  runOptions.picturesDir = pictures;

  apps::Timer loadTimer;
  std::printf("Loading frames from %s", root.c_str());
  std::fflush(stdout);
  const std::vector<FrameGroup> groups = loadGroups(selection);
  std::size_t frames = 0;
  for (const FrameGroup& g : groups) frames += g.frames.size();
  std::printf(" [done, %.0f ms : %zu groups, %zu frames]\n", loadTimer.elapsedMs(), groups.size(), frames);
  for (const FrameGroup& g : groups) {
    std::printf("  %s: %zu frames, %zu methods + the alpha sweep\n", g.name.c_str(), g.frames.size(), g.methods.size());
  }
  if (frames == 0) throw std::runtime_error("no frame found under '" + root + "'");

  std::vector<ProtocolResult> results;
  std::string markdown = "# lidar_sgm_eval results\n\nGenerated by `lidar_sgm_eval`; every figure is in results.json.\n";
  char settings[360];
  std::snprintf(settings, sizeof(settings),
                "\nLiDAR-SGM methods: backend %s, matched at scale %g%s, alpha mode %s, search range %s.\n",
                toString(resolve(backend)).c_str(), base.scale,
                base.scale == 1.0f ? " (full resolution)" : " (half resolution, disparities brought back to full)",
                toString(base.alphaMode).c_str(), (rangeText(runOptions) + "; per frame in results.json").c_str());
  markdown += settings;
  markdown += "Disparity search: " + searchText(runOptions.config.matcher) + ".\n";
  for (const FrameGroup& g : groups) {
    if (g.frames.empty()) continue;
    apps::Timer timer;
    std::printf("%s: %zu frames\n", g.name.c_str(), g.frames.size());
    results.push_back(runGroup(g, runOptions));
    writeAlphaSweepPlot(results.back(), out + "/plots/alpha_sweep_" + slug(g.name) + ".png");
    // The paper's tables first where the group has them (KITTI142), on the terminal too.
    const std::string paperTables = paperTablesMarkdown(results.back()) + groundTruthCloudMarkdown(results.back());
    if (!paperTables.empty()) std::printf("%s\n", paperTables.c_str());
    markdown += "\n## " + g.name + "\n\n" + g.description + ". Plot: `plots/alpha_sweep_" + slug(g.name) +
                ".png`.\n" + paperTables + "\n" + markdownTable(results.back());
    if (writeConfidencePlot(results.back(), out + "/plots/confidence_" + slug(g.name) + ".png")) {
      markdown += "\n### Confidence\n\nPlot: `plots/confidence_" + slug(g.name) + ".png`.\n\n" +
                  confidenceMarkdown(results.back());
    }
    std::printf("%s [done, %.0f ms]\n", g.name.c_str(), timer.elapsedMs());
  }
  io::writeFileAtomically(out + "/results.md", markdown);
  nlohmann::json json = toJson(results);
  for (std::size_t i = 0; i < results.size(); ++i) json["protocols"][i]["confidence"] = confidenceJson(results[i]);
  // How the LiDAR-SGM methods ran, so that runs at different scales are never mixed up.
  json["settings"] = {{"backend", toString(resolve(backend))},
                      {"scale", base.scale},
                      {"alpha_mode", toString(base.alphaMode)},
                      {"threads", threads},
                      {"disparity_range", toString(config.rangeMode)},
                      {"fixed_num_disparities", runOptions.fixedNumDisparities},
                      {"min_confidence", config.minConfidence},
                      {"sky_filter", config.filters.sky.enabled},
                      {"outlier_filter", config.filters.outliers.enabled}};
  io::writeFileAtomically(out + "/results.json", json.dump(2));
  std::printf("Results in %s: results.md, results.json, plots/, %s\n", out.c_str(), pictures.empty() ? "" : "pictures/");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return lidar_sgm::apps::runTool(run, argc, argv);
}
