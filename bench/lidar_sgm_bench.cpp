// lidar_sgm_bench: time per frame and per stage on a real frame, against OpenCV's StereoSGBM.
//
// By default the KITTI 2015 pair 000000_10 with the GT-sampled 64-beam LiDAR of protocol P1;
// -left/-right/-lidar for other files; -synthetic for the built-in frame (the only input when
// the bench is built without lidar_sgm::io); -frame_dir for a frame saved as PGM files (which
// -export_frame writes), the real frame on a machine without OpenCV; -kitti_frame for a KITTI 2015
// frame with its raw scan, timed whole as the tools run it (Densifier::run with their defaults:
// configurations densifier and densifier_half) in pairs with OpenCV's SGBM. Prints a settings block,
// the median of -runs frames after -warmups frames per configuration as a markdown table for
// BENCHMARK.md and one "result ..." line each for scripts, the peak memory of the fused frame,
// OpenCV's SGBM on the same pair, and with -growth the cost per W*H*D.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_frame.hpp"
#include "bench_system.hpp"
#include "bench_timing.hpp"
#include "common/arguments.hpp"
#include "common/help_version.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "pgm_frame.hpp"

#ifdef LIDAR_SGM_BENCH_HAVE_IO
#include "bench_frame_io.hpp"
#include "bench_whole_frame.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#endif
#ifdef LIDAR_SGM_BENCH_HAVE_OPENCV
#include "bench_opencv_sgbm.hpp"
#endif

namespace lidar_sgm {
namespace bench {
namespace {

// Two untimed frames first by default: the first allocates the matcher's buffers and faults in
// their pages, the second warms the caches; a sequence of frames never pays either again.
constexpr int kDefaultWarmups = 2;
// Idle milliseconds before each frame of a pair with OpenCV: longer than libgomp's workers spin
// after a parallel region (~9 ms here), so that neither library's frame runs beside the other's
// spinning threads (bench_opencv_sgbm.hpp). A camera's 10-100 Hz leaves gaps like it.
constexpr int kDefaultPairIdleMs = 30;
const char* kKittiFrame = "000000_10";

struct Options {
  std::string backend = "auto";
  int threads = 0;
  int runs = 20;
  int warmups = kDefaultWarmups;
  int pairIdleMs = kDefaultPairIdleMs;  ///< idle before each frame of a pair with OpenCV
  int numDisparities = 128;
  int paths = 4;
  bool hiddenLidar = true;  ///< the whole frame's hidden-LiDAR filter (-no_hidden_lidar_filter: off)
  float witnessScale = 0.5f;  ///< its witness's scale (-hidden_lidar_scale)
  bool lidarAnchor = true;    ///< the whole frame's LiDAR-anchored sub-pixel disparity (-no_lidar_anchor: off)
  Parameters gate;  ///< its gatedSearch, gatedSearchMargin and gatedSearchRows: every configuration's
  std::vector<std::string> configs;  ///< keys of the configurations to run; empty: all
  bool synthetic = false;
  int width = 1242;   ///< of the synthetic frame
  int height = 375;
  std::string dataRoot;  ///< empty: $LIDAR_SGM_DATA, else the ../shared/data found at configure time
  std::string left, right, lidar;
  std::string frameDir;     ///< a frame saved as PGM files (pgm_frame.hpp)
  std::string kittiFrame;   ///< a KITTI 2015 frame with its raw scan (bench_whole_frame.hpp)
  std::string exportFrame;  ///< write the frame there as PGM files instead of timing it
  bool growth = false;
};

void printUsage(const char* program) {
  std::printf(
      "usage: %s [input] [options]\n"
      "input (default: KITTI 2015 %s with the LiDAR of protocol P1, from the shared data):\n"
      "  -data ROOT              shared data folder (default $LIDAR_SGM_DATA, else %s)\n"
      "  -left L -right R -lidar D   a rectified 8-bit pair and a KITTI sparse disparity PNG\n"
      "  -frame_dir DIR          DIR/left.pgm, right.pgm (8-bit P5), lidar16.pgm (16-bit P5, x16\n"
      "                          disparity, 0 = no point), as -export_frame writes them; needs no OpenCV\n"
      "  -synthetic [-width 1242 -height 375]   the built-in synthetic frame\n"
      "  -kitti_frame ID         KITTI 2015 training frame ID (e.g. 000007) of ROOT/kitti2015_lidar with its\n"
      "                          raw Velodyne scan; the whole frame as the tools run it (configurations\n"
      "                          densifier, densifier_half: the default with this input), the others on its\n"
      "                          pair and projected scan\n"
      "options:\n"
      "  -export_frame DIR       write the input frame to DIR as -frame_dir reads it, check that it\n"
      "                          reads back identical, and time nothing\n"
      "  -backend auto|cpu|cpu_ref|cuda   (default auto)\n"
      "  -threads N              worker threads, 0 = hardware threads (default 0)\n"
      "  -runs N                 timed frames per configuration, median reported (default 20)\n"
      "  -warmups N              untimed frames before them (default %d)\n"
      "  -pair_idle_ms N         idle ms before each frame paired with OpenCV's, so that neither runs\n"
      "                          beside the other's threads still spinning (default %d; 0: back to back)\n"
      "  -configs LIST           comma list of fused,stereo,lidar,paths8,half, and with -kitti_frame\n"
      "                          densifier,densifier_half (default: all, or with -kitti_frame those two)\n"
      "  -num_disparities N      (default 128)\n"
      "  -paths 4|8              SGM paths of every configuration but paths8 (default 4)\n"
      "  -no_gated_search        every configuration over the whole disparity range (default: fused\n"
      "                          frames with the LiDAR-gated search, Parameters::gatedSearch)\n"
      "  -gated_search_margin M -gated_search_rows R   the gate's margin and rows (default 12, 6)\n"
      "  -no_hidden_lidar_filter the whole frame without the hidden-LiDAR filter (its stereo witness)\n"
      "  -hidden_lidar_scale S   the filter's stereo witness at S times the frame's scale: 0.5 (default),\n"
      "                          0.25 or 1\n"
      "  -no_lidar_anchor        the whole frame without the LiDAR-anchored sub-pixel disparity\n"
      "  -growth                 also time the fused frame at 3 sizes x 2 disparity counts\n"
      "  -h, --help              this help\n"
      "  --version               the tool's name and version\n"
      "Every option also takes the GNU spelling: --runs 5, --runs=5.\n",
      program, kKittiFrame, LIDAR_SGM_SHARED_DATA, kDefaultWarmups, kDefaultPairIdleMs);
}

std::vector<std::string> splitCommas(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

/// The options the bench takes (-h and --version are every tool's).
apps::Arguments parseArguments(int argc, char** argv) {
  return apps::Arguments(argc, argv,
                         {"backend", "threads", "runs", "warmups", "pair_idle_ms", "configs", "num_disparities", "paths", "width",
                          "height", "data", "left", "right", "lidar", "frame_dir", "export_frame", "kitti_frame",
                          "gated_search_margin", "gated_search_rows", "hidden_lidar_scale"},
                         {"synthetic", "growth", "no_gated_search", "no_hidden_lidar_filter", "no_lidar_anchor"});
}

Options optionsFrom(const apps::Arguments& args) {
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  Options o;
  o.backend = args.text("backend", o.backend);
  o.threads = args.integer("threads", o.threads);
  o.runs = args.integer("runs", o.runs);
  o.warmups = args.integer("warmups", o.warmups);
  o.pairIdleMs = args.integer("pair_idle_ms", o.pairIdleMs);
  o.configs = splitCommas(args.text("configs", ""));
  o.numDisparities = args.integer("num_disparities", o.numDisparities);
  o.paths = args.integer("paths", o.paths);
  o.width = args.integer("width", o.width);
  o.height = args.integer("height", o.height);
  o.dataRoot = args.text("data", o.dataRoot);
  o.left = args.text("left", o.left);
  o.right = args.text("right", o.right);
  o.lidar = args.text("lidar", o.lidar);
  o.frameDir = args.text("frame_dir", o.frameDir);
  o.exportFrame = args.text("export_frame", o.exportFrame);
  o.kittiFrame = args.text("kitti_frame", o.kittiFrame);
  o.synthetic = args.has("synthetic");
  o.growth = args.has("growth");
  o.gate.gatedSearch = !args.has("no_gated_search");
  o.hiddenLidar = !args.has("no_hidden_lidar_filter");
  o.lidarAnchor = !args.has("no_lidar_anchor");
  o.witnessScale = static_cast<float>(args.number("hidden_lidar_scale", o.witnessScale));
  o.gate.gatedSearchMargin = args.integer("gated_search_margin", o.gate.gatedSearchMargin);
  o.gate.gatedSearchRows = args.integer("gated_search_rows", o.gate.gatedSearchRows);
  if (o.runs < 1) throw std::invalid_argument("-runs must be at least 1");
  if (o.warmups < 0) throw std::invalid_argument("-warmups must be at least 0");
  if (o.pairIdleMs < 0 || o.pairIdleMs > 10000) throw std::invalid_argument("-pair_idle_ms must be in [0, 10000]");
  if (o.width < 16 || o.height < 16) throw std::invalid_argument("-width and -height must be at least 16");
  const int filesGiven = !o.left.empty() + !o.right.empty() + !o.lidar.empty();
  if (filesGiven != 0 && filesGiven != 3) throw std::invalid_argument("-left, -right and -lidar go together");
  const int inputsGiven = (filesGiven == 3) + o.synthetic + !o.frameDir.empty() + !o.kittiFrame.empty();
  if (inputsGiven > 1) {
    throw std::invalid_argument("-synthetic, -left/-right/-lidar, -frame_dir and -kitti_frame exclude each other");
  }
  return o;
}

#ifdef LIDAR_SGM_BENCH_HAVE_IO
/// As the tests find it: -data, else $LIDAR_SGM_DATA, else the ../shared/data of configure time.
std::string dataRoot(const Options& o) {
  if (!o.dataRoot.empty()) return o.dataRoot;
  if (const char* env = std::getenv("LIDAR_SGM_DATA")) return env;
  return LIDAR_SGM_SHARED_DATA;
}
#endif

#ifdef LIDAR_SGM_BENCH_HAVE_IO
/// The pair of a whole frame with its scan projected as the tools project it, for the
/// configurations that time the matcher's part.
Frame projectedFrame(const WholeFrame& whole) {
  Densifier densifier;
  densifier.setCalibration(whole.calibration);
  densifier.setStereoPair(whole.pair.left.view(), whole.pair.right.view());
  densifier.setComputeCloud(false);
  densifier.run(whole.points);
  Frame frame = whole.pair;
  frame.lidar = densifier.projected().lidarPoints();
  frame.source += ", projected as the tools project it";
  return frame;
}
#endif

Frame loadFrame(const Options& o) {
  if (o.synthetic) return makeSyntheticFrame(o.width, o.height);
  if (!o.frameDir.empty()) return readPgmFrame(o.frameDir);
#ifdef LIDAR_SGM_BENCH_HAVE_IO
  if (!o.left.empty()) return loadFileFrame(o.left, o.right, o.lidar);
  return loadKittiP1Frame(dataRoot(o), kKittiFrame);
#else
  throw std::runtime_error(
      "this lidar_sgm_bench was built without lidar_sgm::io (OpenCV not found), so it cannot read frames; "
      "run it with -frame_dir DIR (a frame another build wrote with -export_frame) or -synthetic");
#endif
}

// ---------------------------------------------------------------------------------------------
// Configurations: one row of the table each

struct Config {
  std::string key;    ///< its name for -configs
  std::string label;  ///< its row in the table
  MatchMode mode;     ///< asserted after every frame
  Parameters params;
};

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// Every configuration, fused first: the peak memory printed after it is then that frame's.
std::vector<Config> allConfigs(const Parameters& base, const Frame& frame) {
  Parameters paths8 = base;
  paths8.paths = 8;
  Parameters half = base;
  half.scale = 0.5f;
  // The matcher matches ceil(W/2) x ceil(H/2) with half the disparities at scale 0.5.
  const std::string halfSize = sizeText((frame.width() + 1) / 2, (frame.height() + 1) / 2);
  return {
      {"fused", "fused", MatchMode::Fused, base},
      {"stereo", "stereo-only", MatchMode::StereoOnly, base},
      {"lidar", "LiDAR-only", MatchMode::LidarOnly, base},
      {"paths8", "fused, 8 paths", MatchMode::Fused, paths8},
      {"half", "fused, half scale (" + halfSize + ", " + std::to_string(base.numDisparities / 2) + " disp.)",
       MatchMode::Fused, half},
  };
}

/// The configurations -configs names, in allConfigs()' order; each validated now, so that a bad
/// value stops the bench before minutes of timing rather than after.
/// The configurations that time the whole frame (-kitti_frame), at full and half scale.
const std::vector<std::pair<std::string, float>>& wholeFrameConfigs() {
  static const std::vector<std::pair<std::string, float>> configs = {{"densifier", 1.0f}, {"densifier_half", 0.5f}};
  return configs;
}

bool isWholeFrameConfig(const std::string& key) {
  for (const auto& c : wholeFrameConfigs()) {
    if (c.first == key) return true;
  }
  return false;
}

std::vector<Config> selectConfigs(const std::vector<Config>& all, const std::vector<std::string>& keys) {
  for (const std::string& key : keys) {
    bool known = isWholeFrameConfig(key);
    for (const Config& c : all) known = known || c.key == key;
    if (!known) {
      throw std::invalid_argument("-configs: unknown configuration '" + key +
                                  "'; known: fused,stereo,lidar,paths8,half,densifier,densifier_half");
    }
  }
  std::vector<Config> selected;
  for (const Config& c : all) {
    bool wanted = keys.empty();
    for (const std::string& key : keys) wanted = wanted || c.key == key;
    if (!wanted) continue;
    const std::string problem = validationError(c.params);
    if (!problem.empty()) throw std::invalid_argument("configuration " + c.key + ": " + problem);
    selected.push_back(c);
  }
  return selected;
}

// ---------------------------------------------------------------------------------------------
// Output

std::string ms(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), value >= 100.0 ? "%.1f" : "%.2f", value);
  return text;
}

void printSettings(const Options& o, const Frame& frame, Backend backend, const Parameters& base,
                   const std::vector<Config>& configs) {
  const unsigned hardware = std::thread::hardware_concurrency();
  std::printf("lidar_sgm_bench (%s build)\n", LIDAR_SGM_BENCH_BUILD_TYPE);
  std::printf("  cpu:          %s, %u hardware threads\n", cpuModel().c_str(), hardware);
  std::printf("  isa:          %s (chosen at run time by the cpu backend%s)\n", simdTarget().c_str(),
              backend == Backend::Cpu ? "" : ", which this run does not use");
  std::printf("  backend:      %s -> %s\n", o.backend.c_str(), toString(backend).c_str());
  std::printf("  timed:        %s\n", FrameRunner::timedApi());
  std::printf("  threads:      %d (-threads %d%s)%s\n", effectiveThreads(base), o.threads,
              o.threads == 0 ? " = the hardware's" : "",
              backend == Backend::CpuRef ? ", but cpu_ref runs on one" : "");
  std::printf("  input:        %s\n", frame.source.c_str());
  for (const auto& file : frame.files) std::printf("    %-6s      %s\n", file.first.c_str(), file.second.c_str());
  if (configs.empty()) {
    // The whole frame only: Densifier::run projects the raw scan and takes the range from it in
    // every frame, as the tools do (the table gives the range of each configuration).
    std::printf("  image:        %s, 8-bit gray; the raw scan, projected in each frame by Densifier::run\n",
                sizeText(frame.width(), frame.height()).c_str());
    std::printf("  disparities:  from the LiDAR in each frame, as the tools (the table's column)\n");
  } else {
    std::printf("  image:        %s, 8-bit gray; %zu LiDAR points (%.2f %% of the pixels)\n",
                sizeText(frame.width(), frame.height()).c_str(), frame.lidar.size(),
                100.0 * static_cast<double>(frame.lidar.size()) / (static_cast<double>(frame.width()) * frame.height()));
    std::printf("  disparities:  %d (from %d), fixed: the tools take the range from the LiDAR by default,\n"
                "                the bench times a given one (OpenCV SGBM searches the same)\n",
                base.numDisparities, base.minDisparity);
  }
  std::printf("  paths:        %d (8 in the \"fused, 8 paths\" row)\n", base.paths);
  if (base.gatedSearch) {
    std::printf("  search:       fused frames LiDAR-gated (-gated_search_margin %d -gated_search_rows %d); others: the full range\n",
                base.gatedSearchMargin, base.gatedSearchRows);
  } else {
    std::printf("  search:       the full range at every pixel (-no_gated_search)\n");
  }
  std::printf("  mode:         ");
  for (std::size_t i = 0; i < configs.size(); ++i) std::printf("%s%s", i ? "; " : "", configs[i].label.c_str());
  if (configs.empty()) std::printf("the whole frame only (below)");
  std::printf("\n  timing:       median of %d frames after %d warm-up frames, per configuration\n", o.runs, o.warmups);
}

struct Row {
  std::string label;
  Measurement m;
  bool halfScale;
};

void printTable(const std::vector<Row>& rows) {
  std::printf("\n| config | frame ms | kernel ms | transfers ms |");
  for (const StageColumn& c : stageColumns()) std::printf(" %s |", c.name);
  std::printf(" rescale |\n| --- | ---: | ---: | ---: |");
  for (std::size_t i = 0; i < stageColumns().size(); ++i) std::printf(" ---: |");
  std::printf(" ---: |\n");
  for (const Row& r : rows) {
    std::printf("| %s | %s | %s | %s |", r.label.c_str(), ms(r.m.frameMs).c_str(), ms(r.m.kernelMs).c_str(),
                ms(r.m.transfersMs).c_str());
    for (const StageColumn& c : stageColumns()) std::printf(" %s |", ms(r.m.stages.*c.member).c_str());
    std::printf(" %s |\n", r.halfScale ? ms(r.m.rescaleMs).c_str() : "-");
  }
  std::printf("\nStage columns: Matcher::lastTimings() in ms, medians; frame ms: wall clock around one frame (see timed), "
              "host<->device copies included. kernel ms: the stages without the copies (total - transfers). "
              "transfers ms: the copies (0 on CPU backends). rescale: Matcher::lastRescaleMs(), the 2x2 downscale of "
              "the inputs and the upscale of the disparity at half scale (in frame ms, not in the stages).\n");
}

/// One line per configuration for scripts (scripts/gpu_check.sh reads them): key=value, ms.
void printResultLine(const Config& c, Backend backend, const Measurement& m, int runs) {
  std::printf("result config=%s backend=%s paths=%d scale=%g disparities=%d runs=%d kernel_ms=%.3f transfers_ms=%.3f "
              "frame_ms=%.3f\n",
              c.key.c_str(), toString(backend).c_str(), c.params.paths, static_cast<double>(c.params.scale),
              c.params.numDisparities, runs, m.kernelMs, m.transfersMs, m.frameMs);
}

#ifdef LIDAR_SGM_BENCH_HAVE_OPENCV
std::optional<double> frameMsOf(const std::vector<Row>& rows, const std::string& label) {
  for (const Row& r : rows) {
    if (r.label == label) return r.m.frameMs;
  }
  return std::nullopt;
}

/// OpenCV's SGBM on the same pair, timed the same way, and our frame time relative to it: the
/// table's medians, and (the figure to quote) frame-by-frame pairs of ours and OpenCV's.
void compareWithOpenCv(const Options& o, const Frame& frame, Backend backend, const Parameters& base,
                       const std::vector<Row>& rows) {
  SgbmSettings settings;
  settings.numDisparities = base.numDisparities;  // the same search range as ours
  const int threads = effectiveThreads(base);
  std::printf("\nOpenCV: %s; %d threads\n", describe(settings).c_str(), threads);
  const double sgbmMs = timeOpenCvSgbm(frame, settings, threads, o.runs, o.warmups);
  std::printf("  frame ms: %s (median of %d after %d warm-up frames)\n", ms(sgbmMs).c_str(), o.runs, o.warmups);
  for (const char* label : {"stereo-only", "fused"}) {
    if (const std::optional<double> ours = frameMsOf(rows, label)) {
      std::printf("  ours / OpenCV, %s, separate medians: %.2f (%s ms / %s ms; < 1: ours is faster)\n", label,
                  *ours / sgbmMs, ms(*ours).c_str(), ms(sgbmMs).c_str());
    }
  }
  std::printf("  paired, %d frames each, ours then OpenCV in turn, each after %d ms idle (median ratio [min, max]):\n",
              o.runs, o.pairIdleMs);
  for (const MatchMode mode : {MatchMode::StereoOnly, MatchMode::Fused}) {
    FrameRunner runner(backend, base, frame, mode);
    const PairedTiming t = pairWithOpenCvSgbm(frame, settings, threads, [&] { runner.run(); }, o.runs, o.warmups,
                                              o.pairIdleMs);
    if (runner.lastMode() != mode) throw std::logic_error("the paired run matched in the wrong mode");
    std::printf("  ours / OpenCV, %-11s: %.2f [%.2f, %.2f] (ours %s ms, OpenCV %s ms)\n", toString(mode).c_str(),
                t.ratio, t.ratioMin, t.ratioMax, ms(t.oursMs).c_str(), ms(t.sgbmMs).c_str());
  }
}
#endif

// ---------------------------------------------------------------------------------------------
// Growth: the fused frame's cost against W*H*D

/// `frame` at `width` x `height`: the real pair resized, or the synthetic frame made at that size.
Frame frameAtSize(const Frame& frame, int width, int height) {
  if (frame.synthetic) return makeSyntheticFrame(width, height);
#ifdef LIDAR_SGM_BENCH_HAVE_IO
  return resizedFrame(frame, width, height);
#else
  throw std::logic_error("a real frame without lidar_sgm::io");
#endif
}

void printGrowth(const Options& o, const Frame& frame, Backend backend, const Parameters& base) {
  std::printf("\nGrowth: fused, %s, median of %d frames after %d warm-up; %s\n", toString(backend).c_str(), o.runs,
              o.warmups, frame.synthetic ? "synthetic frames made at each size" : "the pair resized (INTER_AREA down, "
              "INTER_LINEAR up), the LiDAR points moved and their disparities scaled with it");
  std::printf("\n| size | disparities | frame ms | ns per W*H*D |\n| --- | ---: | ---: | ---: |\n");
  for (const double factor : {0.5, 1.0, 2.0}) {
    const int width = static_cast<int>(std::lround(frame.width() * factor));
    const int height = static_cast<int>(std::lround(frame.height() * factor));
    const Frame sized = frameAtSize(frame, width, height);
    for (const int disparities : {64, 128}) {
      Parameters params = base;
      params.numDisparities = disparities;
      FrameRunner runner(backend, params, sized, MatchMode::Fused);
      const Measurement m = measureFrames(runner, MatchMode::Fused, o.runs, o.warmups);
      const double cells = static_cast<double>(width) * height * disparities;
      std::printf("| %s | %d | %s | %.3f |\n", sizeText(width, height).c_str(), disparities, ms(m.frameMs).c_str(),
                  m.frameMs * 1e6 / cells);
      std::fflush(stdout);
    }
  }
}

// ---------------------------------------------------------------------------------------------

/// Whether `a` and `b` hold the same pixels and the same LiDAR points.
bool sameFrame(const Frame& a, const Frame& b) {
  const auto samePixels = [](const Image<std::uint8_t>& x, const Image<std::uint8_t>& y) {
    return x.width() == y.width() && x.height() == y.height() &&
           std::equal(x.data(), x.data() + static_cast<std::size_t>(x.width()) * x.height(), y.data());
  };
  if (!samePixels(a.left, b.left) || !samePixels(a.right, b.right)) return false;
  if (a.lidar.width() != b.lidar.width() || a.lidar.height() != b.lidar.height() || a.lidar.size() != b.lidar.size()) {
    return false;
  }
  for (int y = 0; y < a.lidar.height(); ++y) {
    for (int x = 0; x < a.lidar.width(); ++x) {
      if (!std::equal(a.lidar.begin(x, y), a.lidar.end(x, y), b.lidar.begin(x, y), b.lidar.end(x, y))) return false;
    }
  }
  return true;
}

/// -export_frame: the input frame as PGM files, read back and compared, so that a frame timed
/// elsewhere from these files is exactly this one.
int exportFrame(const Options& o, const Frame& frame) {
  writePgmFrame(frame, o.exportFrame);
  if (!sameFrame(frame, readPgmFrame(o.exportFrame))) {
    throw std::logic_error(o.exportFrame + ": the frame written does not read back identical");
  }
  std::printf("wrote %s (%s, %zu LiDAR points) to %s [done, read back identical]\n", frame.source.c_str(),
              sizeText(frame.width(), frame.height()).c_str(), frame.lidar.size(), o.exportFrame.c_str());
  return 0;
}

#ifdef LIDAR_SGM_BENCH_HAVE_IO
std::string withCommas(std::size_t n) {
  std::string text = std::to_string(n);
  for (int at = static_cast<int>(text.size()) - 3; at > 0; at -= 3) text.insert(static_cast<std::size_t>(at), ",");
  return text;
}

/// The whole frame as the tools run it, in pairs with OpenCV's SGBM at the scale it matches:
/// the full pair with -num_disparities, or the pair halved (INTER_AREA) with half of them.
void printWholeFrames(const Options& o, const WholeFrame& whole, Backend backend, const Parameters& base,
                      const std::vector<std::string>& keys) {
  const int threads = effectiveThreads(base);
  if (!o.hiddenLidar) std::printf("\nWhole frame without the hidden-LiDAR filter (-no_hidden_lidar_filter).");
  if (!o.lidarAnchor) std::printf("\nWhole frame without the LiDAR-anchored sub-pixel disparity (-no_lidar_anchor).");
  if (o.hiddenLidar && o.witnessScale != 0.5f) {
    std::printf("\nWhole frame with the hidden-LiDAR filter's witness at %g times the frame's scale (-hidden_lidar_scale).",
                static_cast<double>(o.witnessScale));
  }
  std::printf("\nWhole frame: Densifier::run with the tools' defaults (fused; range from the LiDAR; confidence, "
              "sky and outlier filters, minimum confidence; a colored cloud in the LiDAR frame), %s, %d threads;\n"
              "paired with OpenCV's StereoSGBM (stereo only) on the pair at the scale matched, %d threads: %d pairs "
              "after %d warm-up pairs, each frame after %d ms idle (-pair_idle_ms)\n",
              toString(backend).c_str(), threads, threads, o.runs, o.warmups, o.pairIdleMs);
  std::printf("\n| config | frame ms | project | match | of which stereo witness | of which core stages | of which "
              "confidence | of which filters | reproject | disparities | cloud points | OpenCV SGBM ms | paired ratio [min, "
              "max] | peak RSS MiB, Densifier alone / with SGBM |\n"
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  std::fflush(stdout);
  double fullSgbmMs = 0.0;  // OpenCV's full-scale frame and our half-scale one, when both ran
  double halfFrameMs = 0.0;
  for (const auto& config : wholeFrameConfigs()) {
    bool wanted = keys.empty();
    for (const std::string& key : keys) wanted = wanted || key == config.first;
    if (!wanted) continue;
    const float scale = config.second;
    SgbmSettings sgbm;
    sgbm.numDisparities = base.numDisparities;
    Frame sgbmPair = whole.pair;
    if (scale != 1.0f) {
      sgbm.numDisparities = base.numDisparities / 2;
      sgbmPair = resizedFrame(whole.pair, (whole.pair.width() + 1) / 2, (whole.pair.height() + 1) / 2);
    }
    const WholeFrameMeasurement m =
        measureWholeFrame(whole, backend, base, scale, sgbmPair, sgbm, o.runs, o.warmups, o.pairIdleMs, o.hiddenLidar,
                          o.witnessScale, o.lidarAnchor);
    const double peak = peakRssMiB();
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %d | %s | %s (%s, %d disp.) | %.2f [%.2f, %.2f] | %.1f / %.1f |\n",
                config.first.c_str(), ms(m.frameMs).c_str(), ms(m.projectMs).c_str(), ms(m.matchMs).c_str(),
                ms(m.witnessMs).c_str(), ms(m.kernelMs).c_str(), ms(m.confidenceMs).c_str(), ms(m.filtersMs).c_str(),
                ms(m.reprojectMs).c_str(), m.disparities,
                withCommas(m.cloudPoints).c_str(), ms(m.paired.sgbmMs).c_str(),
                sizeText(sgbmPair.width(), sgbmPair.height()).c_str(), sgbm.numDisparities, m.paired.ratio,
                m.paired.ratioMin, m.paired.ratioMax, m.densifierPeakRssMiB, peak);
    std::printf("result config=%s backend=%s scale=%g disparities=%d runs=%d frame_ms=%.3f project_ms=%.3f "
                "match_ms=%.3f witness_ms=%.3f kernel_ms=%.3f filters_ms=%.3f reproject_ms=%.3f sgbm_ms=%.3f ratio=%.3f "
                "points=%zu frame_peak_rss_mib=%.1f peak_rss_mib=%.1f\n",
                config.first.c_str(), toString(backend).c_str(), static_cast<double>(scale), m.disparities, o.runs,
                m.frameMs, m.projectMs, m.matchMs, m.witnessMs, m.kernelMs, m.filtersMs, m.reprojectMs, m.paired.sgbmMs,
                m.paired.ratio,
                m.cloudPoints, m.densifierPeakRssMiB, peak);
    std::fflush(stdout);
    (scale == 1.0f ? fullSgbmMs : halfFrameMs) = scale == 1.0f ? m.paired.sgbmMs : m.frameMs;
  }
  if (fullSgbmMs > 0.0 && halfFrameMs > 0.0) {
    // A user who halves the scale to go faster compares with OpenCV on the pair they have.
    std::printf("\nhalf scale against OpenCV's frame at full scale (separate medians of this run): %.2f ms / %.2f ms "
                "= %.2f\nresult config=densifier_half_vs_full_sgbm half_frame_ms=%.3f full_sgbm_ms=%.3f ratio=%.3f\n",
                halfFrameMs, fullSgbmMs, halfFrameMs / fullSgbmMs, halfFrameMs, fullSgbmMs, halfFrameMs / fullSgbmMs);
  }
  std::printf("\nframe ms: wall clock around Densifier::run, median; project, match, reproject: its "
              "DensificationTimings; stereo witness: the hidden-LiDAR filter's stereo-only match; core stages: "
              "Matcher::lastTimings() of the fused match; filters: "
              "the passes after the matcher (the sky and outlier filters, the LiDAR anchor, the minimum confidence); "
              "match - witness - core stages - filters = the pair check, the LiDAR points dropped and the matcher's "
              "steps around its stages; disparities: the range searched "
              "(full-resolution px); ratio: Densifier frame / OpenCV frame per pair, median [min, max]. peak RSS: the "
              "process's peak after three Densifier frames run alone (frame_peak_rss_mib in the result lines) and after "
              "the pairs with OpenCV's SGBM, whose buffers add to the Densifier's (peak_rss_mib); the first "
              "configuration's are the full frame's when no other configuration ran before it.\n");
}
#endif

int run(const Options& o) {
  std::vector<std::string> wholeKeys;
  std::vector<std::string> matcherKeys;
  for (const std::string& key : o.configs) (isWholeFrameConfig(key) ? wholeKeys : matcherKeys).push_back(key);
  if (!wholeKeys.empty() && o.kittiFrame.empty()) {
    throw std::invalid_argument("-configs " + wholeKeys.front() + " times a whole frame: give -kitti_frame ID");
  }
  [[maybe_unused]] const bool wholeFrames = !o.kittiFrame.empty() && (o.configs.empty() || !wholeKeys.empty());
  // With -kitti_frame and no -configs: the whole-frame configurations only.
  const bool matcherConfigs = !matcherKeys.empty() || (o.configs.empty() && o.kittiFrame.empty());
#ifdef LIDAR_SGM_BENCH_HAVE_IO
  std::optional<WholeFrame> whole;
  if (!o.kittiFrame.empty()) whole = loadKitti2015LidarFrame(dataRoot(o), o.kittiFrame);
  // The projection runs a Densifier: only when the matcher's configurations need its points, so
  // that the peak memory before the whole frames is the inputs' alone.
  const bool project = whole && (matcherConfigs || !o.exportFrame.empty());
  const Frame frame = !whole ? loadFrame(o) : project ? projectedFrame(*whole) : whole->pair;
#else
  if (!o.kittiFrame.empty()) throw std::runtime_error("-kitti_frame needs a lidar_sgm_bench built with lidar_sgm::io");
  const Frame frame = loadFrame(o);
#endif
  if (!o.exportFrame.empty()) return exportFrame(o, frame);
  const Backend backend = resolve(backendFromString(o.backend));
  if (!isAvailable(backend)) {
    throw std::runtime_error("backend " + toString(backend) + " is not built into this library");
  }
  Parameters base;
  base.numDisparities = o.numDisparities;
  base.paths = o.paths;
  base.threads = o.threads;
  base.gatedSearch = o.gate.gatedSearch;
  base.gatedSearchMargin = o.gate.gatedSearchMargin;
  base.gatedSearchRows = o.gate.gatedSearchRows;
  validate(base);
  const std::vector<Config> configs =
      matcherConfigs ? selectConfigs(allConfigs(base, frame), matcherKeys) : std::vector<Config>{};

  printSettings(o, frame, backend, base, configs);
  std::printf("  memory:       peak RSS after loading, before the first frame: %.1f MiB\n\n", peakRssMiB());
  std::fflush(stdout);

  std::vector<Row> rows;
  for (const Config& c : configs) {
    FrameRunner runner(backend, c.params, frame, c.mode);
    const Measurement m = measureFrames(runner, c.mode, o.runs, o.warmups);
    std::printf("  %-40s %s ms\n", c.label.c_str(), ms(m.frameMs).c_str());
    printResultLine(c, backend, m, o.runs);
    if (c.key == "fused") {
      // Printed before any other configuration runs, so it is the fused full-size frame's.
      std::printf("  memory: peak RSS after the fused frames: %.1f MiB\n", peakRssMiB());
    }
    std::fflush(stdout);
    rows.push_back({c.label, m, c.params.scale != 1.0f});
  }
#ifdef LIDAR_SGM_BENCH_HAVE_IO
  if (wholeFrames) printWholeFrames(o, *whole, backend, base, wholeKeys);
#endif
  if (!rows.empty()) {
    printTable(rows);
#ifdef LIDAR_SGM_BENCH_HAVE_OPENCV
    compareWithOpenCv(o, frame, backend, base, rows);
#else
    std::printf("\nOpenCV: not found at build time, no StereoSGBM comparison\n");
#endif
  }
  if (o.growth) printGrowth(o, frame, backend, base);
  return 0;
}

}  // namespace
}  // namespace bench
}  // namespace lidar_sgm

int main(int argc, char** argv) {
  try {
    const lidar_sgm::apps::Arguments args = lidar_sgm::bench::parseArguments(argc, argv);
    if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_bench", [&] { lidar_sgm::bench::printUsage(argv[0]); })) {
      return 0;
    }
    return lidar_sgm::bench::run(lidar_sgm::bench::optionsFrom(args));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lidar_sgm_bench: %s\n", e.what());
    return 1;
  }
}
