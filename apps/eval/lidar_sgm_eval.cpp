// lidar_sgm_eval: the evaluation protocols of EVALUATION.md (P1: GT frames with simulated LiDAR,
// P2: real LiDAR with every 4th ring held out, P3: the project's synthetic scenes), every method
// side by side, an alpha sweep per group of frames, pictures, markdown tables and a JSON file.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/arguments.hpp"
#include "common/help_version.hpp"
#include "common/sgm_options.hpp"
#include "common/timer.hpp"
#include "eval/methods.hpp"
#include "eval/pictures.hpp"
#include "eval/plots.hpp"
#include "eval/protocols.hpp"
#include "eval/report.hpp"
#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/version.hpp"

namespace fs = std::filesystem;
using namespace lidar_sgm;
using namespace lidar_sgm::evaluation;

namespace {

void printHelp(const char* program) {
  std::printf(
      "Syntax is: %s -out DIR [options]\n"
      "Runs the evaluation protocols of EVALUATION.md and writes tables, plots, pictures and JSON.\n"
      "The whole plan takes minutes (BENCHMARK.md); it is printed before anything runs.\n"
      "where options are:\n"
      "  -out DIR           output folder, required (the documented run: -out out/eval)\n"
      "  -data ROOT         third-party data root (default: %s)\n"
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
      "  -h, --help         this help\n"
      "  --version          the tool's name and version\n"
      "Every option also takes the GNU spelling: --out DIR, --out=DIR.\n",
      program, LIDAR_SGM_DEFAULT_DATA_ROOT);
}

/// The frames of one table: a protocol on one kind of data (medians never mix kinds).
struct Group {
  std::string name;         ///< "P1 KITTI", "P3 rain 64", ...
  std::string description;
  std::vector<EvalFrame> frames;
  std::vector<Method> methods;  ///< besides the alpha sweep of LiDAR-SGM
};

std::vector<Method> baseMethods() {
  return {{MethodKind::StereoSgm, 0.0}, {MethodKind::LidarSgm, 1.0}, {MethodKind::OpenCvSgbm, 0.0},
          {MethodKind::Morphological, 0.0}};
}

std::string slug(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
  return s;
}

/// All results of one frame: per method, and the sweep (alpha -> metrics).
struct FrameRun {
  FrameResult result;
  std::vector<std::pair<double, eval::DisparityMetrics>> sweep;
  std::map<std::string, Image<std::int16_t>> disparities;  ///< kept for the pictures
};

eval::DisparityMetrics score(const EvalFrame& f, const Image<std::int16_t>& d) {
  return eval::evaluateDisparity(d.view(), f.groundTruth.view(), f.exclude.view());
}

FrameRun runFrame(const EvalFrame& frame, const std::vector<Method>& methods, const std::vector<double>& alphas,
                  const Parameters& base, Backend backend) {
  FrameRun run;
  run.result.dataset = frame.dataset;
  run.result.frame = frame.name;
  for (const Method& m : methods) {
    MethodOutput out = runMethod(m, frame, base, backend);
    run.result.methods.push_back({m.name(), score(frame, out.disparity), out.milliseconds});
    run.disparities[m.name()] = std::move(out.disparity);
  }
  for (double alpha : alphas) {
    const Method fused{MethodKind::FusedSgm, alpha};
    MethodOutput out = runMethod(fused, frame, base, backend);
    run.sweep.emplace_back(alpha, score(frame, out.disparity));
    if (std::abs(alpha - 0.7) < 1e-9) {
      run.result.methods.push_back({fused.name(), run.sweep.back().second, out.milliseconds});
      run.disparities[fused.name()] = std::move(out.disparity);
    }
  }
  return run;
}

cv::Mat groundTruthPicture(const EvalFrame& f) {
  Image<std::int16_t> gt(f.groundTruth.width(), f.groundTruth.height(), kInvalidDisparity);
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      const float d = f.groundTruth(x, y);
      if (d > 0.0f) gt(x, y) = static_cast<std::int16_t>(std::lround(d * kDisparityScale));
    }
  }
  return io::colorizeDisparity(gt.view(), f.numDisparities);
}

void writePicture(const std::string& dir, const EvalFrame& f, const FrameRun& run) {
  std::vector<cv::Mat> rows{labelled(f.leftColor, f.dataset + " " + f.name + ": left image"),
                            labelled(groundTruthPicture(f), "ground truth (black: none)")};
  for (const auto& [name, disparity] : run.disparities) {
    rows.push_back(labelled(io::colorizeDisparity(disparity.view(), f.numDisparities), name));
  }
  for (const std::string& name : {std::string("stereo-only SGM"), std::string("LiDAR-SGM (alpha 0.7)")}) {
    const auto it = run.disparities.find(name);
    if (it == run.disparities.end()) continue;
    rows.push_back(labelled(errorMap(it->second.view(), f.groundTruth.view()),
                            "error, " + name + " (blue < 0.19 px ... red > 48 px, black: no GT)"));
  }
  io::writeImageAtomically(dir + "/" + slug(f.dataset + "_" + f.name) + ".png", stack(rows));

  // The README's comparison: stereo-only against fused, disparity and error, without the input
  // image (third-party frames stay out of the repository; only our results go in).
  const auto stereo = run.disparities.find("stereo-only SGM");
  const auto fused = run.disparities.find("LiDAR-SGM (alpha 0.7)");
  if (stereo != run.disparities.end() && fused != run.disparities.end()) {
    io::writeImageAtomically(
        dir + "/" + slug(f.dataset + "_" + f.name) + "_stereo_vs_fused.png",
        stack({labelled(io::colorizeDisparity(stereo->second.view(), f.numDisparities), "stereo-only SGM"),
               labelled(errorMap(stereo->second.view(), f.groundTruth.view()), "stereo-only SGM: error"),
               labelled(io::colorizeDisparity(fused->second.view(), f.numDisparities), "LiDAR-SGM (alpha 0.7)"),
               labelled(errorMap(fused->second.view(), f.groundTruth.view()), "LiDAR-SGM (alpha 0.7): error")}));
  }
}

/// Runs the frames of `group` in parallel on up to `threads` threads, each frame's matcher on an
/// equal share of them (each frame is independent, and the matchers' results do not depend on
/// their thread count, so neither does the result), then assembles the protocol result.
ProtocolResult runGroup(const Group& group, const std::vector<double>& alphas, int threads, const std::string& pictures,
                        Parameters base, Backend backend) {
  const int workers = std::max(1, std::min(threads, static_cast<int>(group.frames.size())));
  base.threads = std::max(1, threads / workers);
  std::vector<FrameRun> runs(group.frames.size());
  std::atomic<std::size_t> next{0};
  std::mutex printMutex;
  std::size_t done = 0;  // progress, counted under printMutex
  std::vector<std::string> errors(group.frames.size());
  auto worker = [&]() {
    for (std::size_t i = next++; i < group.frames.size(); i = next++) {
      try {
        apps::Timer timer;
        runs[i] = runFrame(group.frames[i], group.methods, alphas, base, backend);
        if (!pictures.empty()) writePicture(pictures, group.frames[i], runs[i]);
        std::lock_guard<std::mutex> lock(printMutex);
        std::printf("  [%zu/%zu] %s / %s [done, %.0f ms]\n", ++done, group.frames.size(),
                    group.frames[i].dataset.c_str(), group.frames[i].name.c_str(), timer.elapsedMs());
        std::fflush(stdout);
      } catch (const std::exception& e) {
        errors[i] = group.frames[i].name + ": " + e.what();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < workers; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  for (const std::string& e : errors) {
    if (!e.empty()) throw std::runtime_error(group.name + ", frame " + e);
  }

  ProtocolResult result;
  result.protocol = group.name;
  result.description = group.description;
  std::vector<std::pair<double, eval::DisparityMetrics>> sweepMedians;
  for (std::size_t a = 0; a < alphas.size(); ++a) {
    std::vector<eval::DisparityMetrics> perFrame;
    for (const FrameRun& r : runs) perFrame.push_back(r.sweep[a].second);
    sweepMedians.emplace_back(alphas[a], medianOver(perFrame));
  }
  // The best alpha: highest median "correct", then lowest RMSE.
  std::size_t best = 0;
  for (std::size_t a = 1; a < sweepMedians.size(); ++a) {
    const auto& m = sweepMedians[a].second;
    const auto& b = sweepMedians[best].second;
    if (m.correct > b.correct + 1e-12 || (std::abs(m.correct - b.correct) <= 1e-12 && m.rmse < b.rmse)) best = a;
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    FrameResult frame = runs[i].result;
    char name[64];
    std::snprintf(name, sizeof(name), "LiDAR-SGM (best alpha %.1f)", alphas[best]);
    frame.methods.push_back({name, runs[i].sweep[best].second, 0.0});
    result.frames.push_back(frame);
  }
  result.sweeps.push_back({"LiDAR-SGM", sweepMedians});
  return result;
}

cv::Mat sweepPlot(const ProtocolResult& r) {
  const auto& sweep = r.sweeps.front().second;
  PlotSeries correct{"fused: correct [%]", {}, {}, cv::Scalar(180, 119, 31)};
  PlotSeries rmse{"fused: RMSE [px]", {}, {}, cv::Scalar(14, 127, 255)};
  for (const auto& [alpha, m] : sweep) {
    correct.x.push_back(alpha);
    correct.y.push_back(100.0 * m.correct);
    rmse.x.push_back(alpha);
    rmse.y.push_back(m.rmse);
  }
  PlotSpec left;
  left.title = r.protocol + ": correct vs alpha (median)";
  left.xLabel = "alpha (LiDAR weight)";
  left.yLabel = "correct [%]";
  left.series = {correct};
  PlotSpec right = left;
  right.title = r.protocol + ": RMSE vs alpha (median)";
  right.yLabel = "RMSE [px]";
  right.series = {rmse};
  cv::Mat both;
  cv::hconcat(linePlot(left), linePlot(right), both);
  return both;
}

std::vector<Group> buildGroups(const apps::Arguments& args, const std::string& root) {
  std::string protocols = args.text("protocols", "P1,P2,P3");
  const auto wants = [&](const std::string& p) { return ("," + protocols + ",").find("," + p + ",") != std::string::npos; };
  std::vector<Group> groups;
  if (wants("P1")) {
    std::map<std::string, Group> byKind;
    for (EvalFrame& f : loadP1(root)) {
      const std::string kind = f.dataset.rfind("kitti", 0) == 0 ? "KITTI" : f.dataset;
      Group& g = byKind[kind];
      g.name = "P1 " + kind;
      g.description = "GT frames (" + kind + ") with a simulated 64-beam LiDAR sampled from the GT; scored on the other GT pixels";
      g.methods = baseMethods();
      g.frames.push_back(std::move(f));
    }
    for (auto& [kind, g] : byKind) groups.push_back(std::move(g));
  }
  if (wants("P2")) {
    Group g;
    g.name = "P2 real LiDAR";
    g.description = "real KITTI HDL-64 scans: every 4th laser ring held out as GT, the others fed; scored on the held-out rings";
    g.methods = baseMethods();
    g.frames = loadP2(root);
    if (!g.frames.empty()) groups.push_back(std::move(g));
  }
  if (wants("P3")) {
    int width = 1242, height = 375;
    const std::string size = args.text("synth_size", "1242x375");
    if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2) {
      throw std::invalid_argument("option -synth_size: '" + size + "' is not WIDTHxHEIGHT");
    }
    struct Variant { const char* key; const char* name; bool rain; int beams; bool third; };
    const std::string sets = "," + args.text("p3_sets", "clear64,rain64,clear128") + ",";
    for (const Variant v : {Variant{"clear64", "P3 clear 64 beams", false, 64, true},
                            Variant{"rain64", "P3 rain 64 beams", true, 64, false},
                            Variant{"clear128", "P3 clear 128 beams", false, 128, false}}) {
      if (sets.find(std::string(",") + v.key + ",") == std::string::npos) continue;
      P3Options o;
      o.frames = args.integer("synth_frames", 10);
      o.rain = v.rain;
      o.beams = v.beams;
      o.thirdCamera = v.third;
      o.width = width;
      o.height = height;
      Group g;
      g.name = v.name;
      g.description = std::string("synthetic streets with exact GT, ") + (v.rain ? "rain" : "clear") + ", " +
                      std::to_string(v.beams) + "-beam LiDAR" + (v.third ? ", third camera 0.20 m above the left" : "");
      g.methods = baseMethods();
      if (v.third) {
        g.methods.push_back({MethodKind::ThreeCameras, 0.0});
        g.methods.push_back({MethodKind::ThreeCamerasLidar, 0.7});
      }
      g.frames = loadP3(o);
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

/// The comma-separated `option`'s items, each checked against `known`.
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

/// What the run will do, before it loads anything: it takes minutes, so it never starts unseen.
void printPlan(const apps::Arguments& args, const std::string& root, const std::string& out,
               const std::vector<double>& alphas, Backend backend, const Parameters& base, int threads) {
  const std::vector<std::string> protocols = listOption(args, "protocols", "P1,P2,P3");
  const std::vector<std::string> sets = listOption(args, "p3_sets", "clear64,rain64,clear128");
  const bool threeCameras = std::find(protocols.begin(), protocols.end(), "P3") != protocols.end() &&
                            std::find(sets.begin(), sets.end(), "clear64") != sets.end();
  std::vector<std::string> methods;
  for (const Method& m : baseMethods()) methods.push_back(m.name());
  std::vector<std::string> sweep;
  for (double a : alphas) sweep.push_back(std::to_string(a).substr(0, 4));
  std::printf("lidar_sgm_eval %s: the plan\n", versionString());
  std::printf("  protocols: %s\n", joinedText(protocols, ", ").c_str());
  for (const std::string& p : protocols) {
    if (p == "P1") std::printf("    P1: every GT frame under %s, simulated 64-beam LiDAR\n", root.c_str());
    if (p == "P2") std::printf("    P2: the real KITTI scans under %s, every 4th ring held out\n", root.c_str());
    if (p == "P3") {
      std::printf("    P3: synthetic sets %s, %d frames each (seeds 100..), %s\n", joinedText(sets, ", ").c_str(),
                  args.integer("synth_frames", 10), args.text("synth_size", "1242x375").c_str());
    }
  }
  std::printf("  methods:   %s; LiDAR-SGM at alpha %s%s\n", joinedText(methods, ", ").c_str(),
              joinedText(sweep, ", ").c_str(), threeCameras ? "; on P3 clear64 also the three-camera methods" : "");
  std::printf("  matcher:   backend %s, scale %g, %d threads in all\n", toString(resolve(backend)).c_str(), base.scale,
              threads);
  std::printf("  outputs:   %s/results.md, %s/results.json, %s/plots/%s\n", out.c_str(), out.c_str(), out.c_str(),
              args.has("no_pictures") ? "" : (", " + out + "/pictures/").c_str());
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  const apps::Arguments args(
      argc, argv,
      apps::joined(apps::sgmValueOptions(),
                   {"data", "out", "protocols", "synth_frames", "synth_size", "p3_sets", "alpha_step"}),
      apps::joined(apps::sgmFlagOptions(), {"no_pictures"}));
  if (apps::answerHelpOrVersion(args, "lidar_sgm_eval", [&] { printHelp(argv[0]); })) return 0;
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  const std::string root = args.text("data", LIDAR_SGM_DEFAULT_DATA_ROOT);
  // Required: the run takes minutes and writes a folder, so it never starts by accident.
  const std::string out = args.text("out", "");
  // The matcher parameters of every LiDAR-SGM method (alpha is the method's; numDisparities the
  // frame's; threads are shared out by runGroup).
  const Parameters base = apps::parametersFrom(args);
  const Backend backend = apps::backendFrom(args);
  const double step = args.number("alpha_step", 0.1);
  if (!(step > 0.0 && step <= 1.0)) throw std::invalid_argument("option -alpha_step: must be in (0, 1]");
  const int threads = effectiveThreads(base);  // -threads, validated with the SGM options
  std::vector<double> alphas;
  for (int i = 0; i * step <= 1.0 + 1e-9; ++i) alphas.push_back(std::min(1.0, std::round(i * step * 1000) / 1000));
  if (std::find_if(alphas.begin(), alphas.end(), [](double a) { return std::abs(a - 0.7) < 1e-9; }) == alphas.end()) {
    alphas.push_back(0.7);  // the paper's alpha is always in the table
    std::sort(alphas.begin(), alphas.end());
  }
  printPlan(args, root, out.empty() ? "DIR" : out, alphas, backend, base, threads);
  if (out.empty()) {
    throw std::invalid_argument("nothing run: -out DIR is required, the folder for the results above "
                                "(e.g. -out out/eval; -h for every option)");
  }
  fs::create_directories(out + "/plots");
  const std::string pictures = args.has("no_pictures") ? "" : out + "/pictures";
  if (!pictures.empty()) fs::create_directories(pictures);

  apps::Timer loadTimer;
  std::printf("Loading frames from %s", root.c_str());
  std::fflush(stdout);
  const std::vector<Group> groups = buildGroups(args, root);
  std::size_t frames = 0;
  for (const Group& g : groups) frames += g.frames.size();
  std::printf(" [done, %.0f ms : %zu groups, %zu frames]\n", loadTimer.elapsedMs(), groups.size(), frames);
  for (const Group& g : groups) {
    std::printf("  %s: %zu frames, %zu methods + the alpha sweep\n", g.name.c_str(), g.frames.size(), g.methods.size());
  }
  if (frames == 0) throw std::runtime_error("no frame found under '" + root + "'");

  std::vector<ProtocolResult> results;
  std::string markdown = "# lidar_sgm_eval results\n\nGenerated by `lidar_sgm_eval`; every figure is in results.json.\n";
  char settings[160];
  std::snprintf(settings, sizeof(settings), "\nLiDAR-SGM methods: backend %s, matched at scale %g%s.\n",
                toString(resolve(backend)).c_str(), base.scale,
                base.scale == 1.0f ? " (full resolution)" : " (half resolution, disparities brought back to full)");
  markdown += settings;
  for (const Group& g : groups) {
    if (g.frames.empty()) continue;
    apps::Timer timer;
    std::printf("%s: %zu frames\n", g.name.c_str(), g.frames.size());
    results.push_back(runGroup(g, alphas, threads, pictures, base, backend));
    io::writeImageAtomically(out + "/plots/alpha_sweep_" + slug(g.name) + ".png", sweepPlot(results.back()));
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
