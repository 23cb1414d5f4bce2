// lidar_sgm_eval: the evaluation protocols of EVALUATION.md (P1: GT frames with simulated LiDAR,
// P2: real LiDAR with every 4th ring held out, P3: the project's synthetic scenes), every method
// side by side, an alpha sweep per group of frames, pictures, markdown tables and a JSON file.
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/arguments.hpp"
#include "common/sgm_options.hpp"
#include "common/timer.hpp"
#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/eval/groups.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace fs = std::filesystem;
using namespace lidar_sgm;
using namespace lidar_sgm::eval;

namespace {

void printHelp(const char* program) {
  std::printf(
      "Syntax is: %s [options]\n"
      "Runs the evaluation protocols of EVALUATION.md and writes tables, plots, pictures and JSON.\n"
      "where options are:\n"
      "  -data ROOT         third-party data root (default: $LIDAR_SGM_DATA, else ../shared/data, relative to\n"
      "                     the working directory)\n"
      "  -out DIR           output folder (default: out/eval)\n"
      "  -protocols LIST    comma-separated subset of P1,P2,P3 (default: P1,P2,P3)\n"
      "  -synth_frames N    synthetic frames per P3 set (default: 10, seeds 100..)\n"
      "  -synth_size WxH    synthetic frame size (default: 1242x375)\n"
      "  -p3_sets LIST      comma-separated subset of clear64,rain64,clear128 (default: all three;\n"
      "                     clear64 has the third camera for Triple-SGM)\n"
      "  -alpha_step S      alpha sweep step in (0, 1] (default: 0.1)\n"
      "  -threads N         threads in all, 0 = all hardware threads (default: 0): frames run in parallel and\n"
      "                     each frame's matcher gets an equal share of the rest; results do not depend on it\n"
      "  -scale 1|0.5       match the LiDAR-SGM methods at full or half resolution (0.5: the paper's fast\n"
      "                     mode; each frame's search range is rounded up to a multiple of 32) (default: 1)\n"
      "  -backend NAME      the LiDAR-SGM methods' backend: auto, cpu_ref, cpu or cuda (default: auto)\n"
      "  -no_pictures       skip the per-frame pictures\n"
      "  and every SGM option of lidar_sgm_disparity (-sigma, -p1, -p2, -no_lr_check, ...) for the LiDAR-SGM methods\n"
      "  -h                 this help\n",
      program);
}

/// A comma-separated option value as its items.
std::vector<std::string> listOption(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) items.push_back(item);
  return items;
}

GroupSelection selectionFrom(const apps::Arguments& args, const std::string& root) {
  GroupSelection selection;
  selection.dataRoot = root;
  selection.protocols = listOption(args.text("protocols", "P1,P2,P3"));
  selection.p3Sets = listOption(args.text("p3_sets", "clear64,rain64,clear128"));
  selection.synthFrames = args.integer("synth_frames", 10);
  const std::string size = args.text("synth_size", "1242x375");
  if (std::sscanf(size.c_str(), "%dx%d", &selection.synthWidth, &selection.synthHeight) != 2) {
    throw std::invalid_argument("option -synth_size: '" + size + "' is not WIDTHxHEIGHT");
  }
  return selection;
}

int run(int argc, char** argv) {
  const apps::Arguments args(
      argc, argv,
      apps::joined(apps::sgmValueOptions(),
                   {"data", "out", "protocols", "synth_frames", "synth_size", "p3_sets", "alpha_step"}),
      apps::joined(apps::sgmFlagOptions(), {"h", "help", "no_pictures"}));
  if (args.has("h") || args.has("help")) {
    printHelp(argv[0]);
    return 0;
  }
  const std::string root = resolveDataRoot(args.text("data", ""));
  const std::string out = args.text("out", "out/eval");
  // The matcher parameters of every LiDAR-SGM method (alpha is the method's; numDisparities the
  // frame's; threads are shared out by runGroup).
  const Parameters base = apps::parametersFrom(args);
  const Backend backend = apps::backendFrom(args);
  const double step = args.number("alpha_step", 0.1);
  if (!(step > 0.0 && step <= 1.0)) throw std::invalid_argument("option -alpha_step: must be in (0, 1]");
  const int threads = effectiveThreads(base);  // -threads, validated with the SGM options
  GroupRunOptions runOptions;
  runOptions.alphas = sweepAlphas(step);
  runOptions.threads = threads;
  runOptions.base = base;
  runOptions.backend = backend;
  fs::create_directories(out + "/plots");
  const std::string pictures = args.has("no_pictures") ? "" : out + "/pictures";
  if (!pictures.empty()) fs::create_directories(pictures);
  runOptions.picturesDir = pictures;

  apps::Timer loadTimer;
  std::printf("Loading frames from %s", root.c_str());
  std::fflush(stdout);
  const std::vector<FrameGroup> groups = loadGroups(selectionFrom(args, root));
  std::size_t frames = 0;
  for (const FrameGroup& g : groups) frames += g.frames.size();
  std::printf(" [done, %.0f ms : %zu groups, %zu frames]\n", loadTimer.elapsedMs(), groups.size(), frames);
  if (frames == 0) throw std::runtime_error("no frame found under '" + root + "'");

  std::vector<ProtocolResult> results;
  std::string markdown = "# lidar_sgm_eval results\n\nGenerated by `lidar_sgm_eval`; every figure is in results.json.\n";
  char settings[160];
  std::snprintf(settings, sizeof(settings), "\nLiDAR-SGM methods: backend %s, matched at scale %g%s.\n",
                toString(resolve(backend)).c_str(), base.scale,
                base.scale == 1.0f ? " (full resolution)" : " (half resolution, disparities brought back to full)");
  markdown += settings;
  for (const FrameGroup& g : groups) {
    if (g.frames.empty()) continue;
    apps::Timer timer;
    std::printf("%s: %zu frames\n", g.name.c_str(), g.frames.size());
    results.push_back(runGroup(g, runOptions));
    writeAlphaSweepPlot(results.back(), out + "/plots/alpha_sweep_" + slug(g.name) + ".png");
    markdown += "\n## " + g.name + "\n\n" + g.description + ". Plot: `plots/alpha_sweep_" + slug(g.name) +
                ".png`.\n\n" + markdownTable(results.back());
    std::printf("%s [done, %.0f ms]\n", g.name.c_str(), timer.elapsedMs());
  }
  writeTextAtomically(out + "/results.md", markdown);
  nlohmann::json json = toJson(results);
  // How the LiDAR-SGM methods ran, so that runs at different scales are never mixed up.
  json["settings"] = {{"backend", toString(resolve(backend))}, {"scale", base.scale}, {"threads", threads}};
  writeTextAtomically(out + "/results.json", json.dump(2));
  std::printf("Results in %s: results.md, results.json, plots/, %s\n", out.c_str(), pictures.empty() ? "" : "pictures/");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nError: %s\n", e.what());
    return 1;
  }
}
