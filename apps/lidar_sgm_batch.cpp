// lidar_sgm_batch: every frame of a sequence densified in one call, as lidar_sgm_densify densifies
// one (the same options, the same clouds byte for byte), resumable and sharded.
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <thread>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <pcl/console/print.h>

#include "batch/batch_frame.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/frame_runner.hpp"
#include "lidar_sgm/sequence/manifest.hpp"
#include "lidar_sgm/sequence/output_lock.hpp"
#include "batch/output_state.hpp"
#include "batch/progress.hpp"
#include "batch/sequence_map.hpp"
#include "common/arguments.hpp"
#include "common/help_layout.hpp"
#include "common/help_version.hpp"
#include "common/output_paths.hpp"
#include "common/config_arguments.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "densify/densify_options.hpp"
#include "lidar_sgm/io/output_transaction.hpp"

namespace fs = std::filesystem;
using lidar_sgm::apps::Arguments;
using lidar_sgm::sequence::Frame;
using lidar_sgm::sequence::FrameRecord;

namespace {

constexpr int kDefaultProgressEvery = 10;

// The signal that asked the run to stop (0: none). The frame under way is finished (its cloud is
// renamed into place only when complete), then the run stops.
volatile std::sig_atomic_t stopSignal = 0;

extern "C" void onStopSignal(int signal) { stopSignal = signal; }

/// SIGINT and SIGTERM stop the run after the current frame; a second one kills it at once
/// (SA_RESETHAND), leaving at most that frame's hidden temporary file.
void installStopHandlers() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void printHelp(const char* program) {
  char usage[1600];
  std::snprintf(
      usage, sizeof(usage),
      "Syntax is: %s (-input_dir DIR | -list FILE) -output_dir OUT <options>\n"
      "Densifies every frame of a sequence as lidar_sgm_densify densifies one (same options, same clouds).\n"
      "A frame without an image pair runs LiDAR-only (colored from a lone left image); a frame whose file is\n"
      "missing or bad is reported and skipped, the others go on. Exit code 0 only when every frame succeeded.\n"
      "Every cloud is written to a temporary file renamed when complete; a re-run skips the frames whose cloud\n"
      "exists. SIGINT/SIGTERM: the current frame is finished, the run stops (exit code 128 + signal).\n",
      program);
  const std::string inputs =
      "  -input_dir DIR           the frames of DIR, by its layout:\n"
      "                             KITTI odometry sequence  NN/{velodyne,image_2,image_3}/, NN/calib.txt\n"
      "                             KITTI odometry root      sequences/NN/... (every sequence; outputs OUT/NN/)\n"
      "                             KITTI raw drive          {velodyne_points,image_02,image_03}/data/, the\n"
      "                                                      calibration in the date folder above the drive\n"
      "                             KITTI object             velodyne/, image_2/, image_3/, calib/NNNNNN.txt\n"
      "                             KITTI stereo 2015        velodyne/NNNNNN_10.bin (raw scans: only those frames),\n"
      "                                                      image_2/, image_3/, and calib_cam_to_cam/NNNNNN.txt\n"
      "                                                      + calib_velo_to_cam/NNNNNN.txt per frame, or one pair\n"
      "                                                      calib/calib_cam_to_cam.txt + calib_velo_to_cam.txt\n"
      "                           scans are .bin, .pcd or .ply; a frame's images are the .png of its stem\n"
      "  -list FILE               a frame per line: SCAN LEFT RIGHT CALIB, '-' for a missing image; '#'\n"
      "                           comments; relative paths from FILE's folder; CALIB as lidar_sgm_densify's\n"
      "  -shard K/N               only frames i with i % N == K (0 <= K < N): N processes cover the sequence\n"
      "                           once, with the same clouds as one process (default: 0/1)\n"
      "  -image_size WxH          image size when neither the calibration nor an image gives it\n" +
      lidar_sgm::apps::inputLimitOptionsHelp();
  char progress[400];
  std::snprintf(progress, sizeof(progress),
                "  -progress N              on a terminal, one progress line redrawn in place on stderr; otherwise a\n"
                "                           progress line every N frames (default: %d)\n",
                kDefaultProgressEvery);
  const std::string outputs =
      std::string(
          "  -output_dir OUT          OUT/<frame>.pcd per frame (created if missing), and the manifest\n"
          "                           OUT/manifest.jsonl (OUT/manifest.shard-K-of-N.jsonl with -shard): a JSON\n"
          "                           line per frame: frame, status ok|skipped|failed, points, timings, error\n"
          "  -overwrite               redo the frames whose cloud exists (default: skip them)\n"
          "  -extension pcd|ply       the clouds' file type (default: pcd)\n") +
      progress + lidar_sgm::apps::outputOptionsHelp() + lidar_sgm::apps::mapOptionsHelp();
  const std::string speed =
      "  -jobs J                  frames densified at once, each on its own worker (0 = one per CPU this\n"
      "                           process may use); the matcher threads of each are -threads, else those\n"
      "                           CPUs shared out; neither changes a cloud (default: 0)\n" +
      lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Speed, lidar_sgm::OptionScope::Cloud);
  const std::vector<lidar_sgm::apps::HelpExample> examples{
      {"A drive rendered by 'lidar_sgm_synth -out drive -sequence 3 -step 1' (KITTI odometry layout), with its map:",
       "lidar_sgm_batch -input_dir drive -output_dir drive_dense -map drive_map.pcd"},
      {"Frames in KITTI's object layout ('lidar_sgm_synth -out frames -n 2'), at half scale, two at once:",
       "lidar_sgm_batch -input_dir frames -output_dir frames_dense -scale 0.5 -jobs 2"},
      {"A KITTI raw drive (its calibration in the date folder above it), the clouds as PLY:",
       "lidar_sgm_batch -input_dir 2011_09_26/2011_09_26_drive_0005_sync -output_dir drive_0005 -extension ply"},
  };
  const std::string text = lidar_sgm::apps::helpText(usage,
                                                     {{"Inputs", inputs},
                                                      {"Outputs", outputs},
                                                      {"Method", lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Method,
                                                                                            lidar_sgm::OptionScope::Cloud)},
                                                      {"Speed", speed},
                                                      {"Filters", lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Filters,
                                                                                             lidar_sgm::OptionScope::Cloud)}},
                                                     examples);
  std::fputs(text.c_str(), stdout);
}

/// -jobs (0 = one per CPU this process may use) and the matcher threads of each (-threads, else
/// those CPUs shared out): results never depend on either.
void jobsAndThreads(const Arguments& args, const lidar_sgm::DensifierConfig& config, int& jobs, int& threads) {
  // The CPUs this process may run on (a Slurm task's or a container's share), not the machine's.
  cpu_set_t cpus;
  const int hardware = sched_getaffinity(0, sizeof(cpus), &cpus) == 0
                           ? std::max(1, CPU_COUNT(&cpus))
                           : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  jobs = args.integer("jobs", 0);
  if (jobs < 0) throw std::invalid_argument("option -jobs: must be >= 0 (0 = one per hardware thread)");
  if (jobs == 0) jobs = hardware;
  threads = args.has("threads") ? config.matcher.threads : std::max(1, hardware / jobs);
}

int run(int argc, char** argv) {
  using lidar_sgm::apps::joined;
  const Arguments args(
      argc, argv,
      joined(joined(lidar_sgm::apps::densifyValueOptions(), lidar_sgm::apps::mapValueOptions()),
             {"input_dir", "list", "output_dir", "shard", "extension", "progress", "jobs"}),
      joined(lidar_sgm::apps::densifyFlagOptions(), {"overwrite"}));
  if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_batch", [&] { printHelp(argv[0]); })) return 0;
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals()[0] +
                                "' (the frames come from -input_dir or -list; see -h)");
  }
  if (args.has("input_dir") == args.has("list")) {
    throw std::invalid_argument("give the frames with either -input_dir DIR or -list FILE (see -h)");
  }
  const std::string outDir = args.text("output_dir", "");
  if (outDir.empty()) throw std::invalid_argument("-output_dir OUT is required");
  // Every bad option is refused before any frame is read.
  const lidar_sgm::DensifierConfig config = lidar_sgm::apps::checkedDensifyOptions(args);
  const lidar_sgm::sequence::Shard shard = lidar_sgm::sequence::parseShard(args.text("shard", "0/1"));
  const lidar_sgm::apps::MapOptions mapOptions = lidar_sgm::apps::mapOptionsFrom(args, shard);
  const int progressEvery = args.integer("progress", kDefaultProgressEvery);
  if (progressEvery < 1) throw std::invalid_argument("option -progress: must be >= 1 (frames)");
  int jobs = 1;
  int threads = 1;
  jobsAndThreads(args, config, jobs, threads);
  const std::string extension = args.text("extension", "pcd");
  if (extension != "pcd" && extension != "ply") {
    throw std::invalid_argument("option -extension: '" + extension + "' must be pcd or ply");
  }
  try {
    lidar_sgm::io::checkCloudOutput("frame." + extension, lidar_sgm::apps::outputOptionsFrom(args).format);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -format: ") + e.what());
  }
  int width = 0;
  int height = 0;
  if (args.has("image_size")) lidar_sgm::apps::parseImageSize(args.text("image_size", ""), width, height);

  const std::string inputPath = args.has("list") ? args.text("list", "") : args.text("input_dir", "");
  const std::vector<Frame> all = args.has("list") ? lidar_sgm::sequence::framesFromList(inputPath)
                                                  : lidar_sgm::sequence::framesFromDirectory(inputPath);
  const lidar_sgm::sequence::Layout layout =
      args.has("list") ? lidar_sgm::sequence::Layout::ListFile : lidar_sgm::sequence::directoryLayout(inputPath);
  std::printf("Input %s: %s, %zu frame(s)\n", inputPath.c_str(), lidar_sgm::sequence::layoutName(layout), all.size());
  std::fflush(stdout);
  const std::vector<Frame> frames = lidar_sgm::sequence::framesOfShard(all, shard);
  std::optional<lidar_sgm::apps::SequenceMap> map;
  if (!mapOptions.mapPath.empty()) {
    map.emplace(mapOptions, all, config.reprojection.frame, width, height);
    std::printf("Poses: %s\n", map->posesSource().c_str());
  }
  fs::create_directories(outDir);
  // Before anything in the folder is read or changed: one run per folder and shard.
  const lidar_sgm::sequence::OutputFolderLock lock(outDir, shard);
  // The options that make a cloud's bytes: the method's and the output's, not how the run is
  // spread (-threads, -backend: every backend gives the same bytes).
  std::set<std::string> cloudOptions = joined(lidar_sgm::apps::densifyValueOptions(), lidar_sgm::apps::densifyFlagOptions());
  cloudOptions.erase("threads");
  cloudOptions.erase("backend");
  cloudOptions.erase("max_points");  // accepts or refuses an input; never changes a cloud's bytes
  lidar_sgm::apps::checkAndRecordCloudOptions(
      outDir, lidar_sgm::apps::cloudOptionsText(args, cloudOptions, extension), args.has("overwrite"));
  std::vector<std::string> outPaths;
  for (const Frame& frame : frames) outPaths.push_back((fs::path(outDir) / (frame.name + "." + extension)).string());
  std::size_t stale = lidar_sgm::apps::removeStaleTemporaries(outPaths);
  if (map) {
    stale += lidar_sgm::io::removeDeadRunTemporaries(mapOptions.mapPath) +
             lidar_sgm::io::removeDeadRunTemporaries(mapOptions.picturePath);
  }
  const std::string manifestName =
      shard.count == 1 ? "manifest.jsonl"
                       : "manifest.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".jsonl";
  // What earlier runs recorded of the frames this one will skip, before its manifest is replaced.
  const std::map<std::string, FrameRecord> earlierRecords =
      args.has("overwrite") ? std::map<std::string, FrameRecord>{} : lidar_sgm::apps::earlierFrameRecords(outDir);
  lidar_sgm::sequence::Manifest manifest((fs::path(outDir) / manifestName).string());
  std::printf("%zu frame(s)", frames.size());
  if (shard.count > 1) std::printf(" (shard %d/%d of %zu)", shard.index, shard.count, all.size());
  std::printf(", output %s", outDir.c_str());
  if (stale > 0) std::printf(" (removed %zu temporary file(s) an interrupted run left)", stale);
  std::printf("\n");
  std::fflush(stdout);

  installStopHandlers();
  const lidar_sgm::apps::Timer runTimer;
  std::vector<std::unique_ptr<lidar_sgm::apps::FrameDensifier>> densifiers;
  // From the whole sequence, not the shard: every shard checks its frames against the same size.
  const std::map<std::string, lidar_sgm::apps::CalibrationImage> shared = lidar_sgm::apps::sharedCalibrationImages(all);
  for (int j = 0; j < jobs; ++j) {
    densifiers.push_back(std::make_unique<lidar_sgm::apps::FrameDensifier>(args, config, width, height, threads, shared));
  }
  const bool overwrite = args.has("overwrite");

  // One frame, whole, on worker `worker`: skipped when its cloud exists, else densified and
  // written; a frame's own failure is its record, not an exception.
  auto work = [&](std::size_t index, int worker) {
    const Frame& frame = frames[index];
    FrameRecord record;
    record.frame = frame.name;
    const std::string& outPath = outPaths[index];
    try {
      if (!overwrite && fs::exists(outPath)) {
        // Only a whole cloud counts as done: one cut short (a full disk) is made again.
        record.redone = lidar_sgm::apps::untrustedCloudReason(outPath, earlierRecords, frame.name);
        if (record.redone.empty()) {
          return lidar_sgm::apps::skippedFrameRecord(frame.name, fs::file_size(outPath), earlierRecords);
        }
      }
      for (const std::string& input : {frame.scan, frame.left, frame.right, frame.calib}) {
        if (!input.empty() && lidar_sgm::apps::samePath(outPath, input)) {
          throw std::invalid_argument("its output '" + outPath + "' is its input; refusing to overwrite an input");
        }
      }
      fs::create_directories(fs::path(outPath).parent_path());
      const lidar_sgm::apps::FrameResult result = densifiers[static_cast<std::size_t>(worker)]->densify(frame, outPath);
      record.status = "ok";
      record.points = result.points;
      record.bytes = result.bytes;
      record.ms = result.ms;
    } catch (const std::exception& e) {
      record.status = "failed";
      record.error = e.what();
    }
    return record;
  };

  lidar_sgm::apps::FrameCounts counts;
  std::uintmax_t bytesWritten = 0;
  lidar_sgm::sequence::FrameTimings summed;
  lidar_sgm::apps::Progress progress(stderr, isatty(fileno(stderr)) != 0, frames.size(), progressEvery);
  // Records arrive here in frame order, on this thread: the log and the manifest read the same
  // whatever -jobs.
  auto done = [&](std::size_t index, const FrameRecord& record) {
    progress.clear();
    // The map reads the cloud back as written: a skipped frame's too.
    if (map && record.status != "failed") map->frameWritten(frames[index], outPaths[index]);
    if (record.status == "ok") {
      ++counts.ok;
      bytesWritten += record.bytes;
      summed.load += record.ms.load;
      summed.project += record.ms.project;
      summed.match += record.ms.match;
      summed.reproject += record.ms.reproject;
      summed.save += record.ms.save;
      std::printf("%s ok [%.0f ms : %zu points, %.2f MB]%s\n", record.frame.c_str(), record.ms.total(), record.points,
                  static_cast<double>(record.bytes) / 1e6,
                  record.redone.empty() ? "" : (" (redone: the earlier cloud " + record.redone + ")").c_str());
    } else if (record.status == "skipped") {
      ++counts.skipped;
      std::printf("%s skipped\n", record.frame.c_str());
    } else {
      ++counts.failed;
      std::printf("%s failed\n", record.frame.c_str());
      std::fflush(stdout);
      std::fprintf(stderr, "Error: frame %s: %s\n", record.frame.c_str(), record.error.c_str());
    }
    std::fflush(stdout);
    manifest.append(record);
    progress.update(counts, runTimer.elapsedMs() / 1000.0);
  };
  lidar_sgm::sequence::runFramesInOrder(frames.size(), jobs, work, done, [] { return stopSignal != 0; });
  progress.finish();

  const double seconds = runTimer.elapsedMs() / 1000.0;
  // A signal during the map's build stops it before anything is written; one during the write
  // lets the map and its picture be finished (they are reported as written).
  const lidar_sgm::apps::MapResult mapResult =
      map && stopSignal == 0 ? map->build([] { return stopSignal != 0; }) : lidar_sgm::apps::MapResult{};
  std::printf("Summary: %zu/%zu frames: %zu ok, %zu skipped, %zu failed", counts.done(), frames.size(), counts.ok,
              counts.skipped, counts.failed);
  if (stopSignal != 0) std::printf(", %zu not run (stopped by signal %d)", frames.size() - counts.done(), int{stopSignal});
  std::printf(" in %.1f s (%.2f frames/s densified, %d job(s) x %d matcher thread(s))\n", seconds,
              seconds > 0.0 ? static_cast<double>(counts.ok + counts.failed) / seconds : 0.0, jobs, threads);
  if (counts.ok > 0) {
    const double n = static_cast<double>(counts.ok);
    std::printf("Per densified frame: %.2f MB written; load %.0f ms, project %.0f ms, match %.0f ms, reproject %.0f ms, "
                "save %.0f ms (on its worker)\n",
                static_cast<double>(bytesWritten) / 1e6 / n, summed.load / n, summed.project / n, summed.match / n,
                summed.reproject / n, summed.save / n);
  }
  std::printf("Manifest: %s\n", manifest.path().c_str());
  if (map && stopSignal != 0 && !mapResult.written) {
    std::printf("Map not built: the run was stopped; run again to finish it\n");
  }
  if (!mapResult.summary.empty()) std::printf("%s\n", mapResult.summary.c_str());
  if (stopSignal != 0) return 128 + stopSignal;
  return counts.failed == 0 && mapResult.ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // Our messages name the problem; PCL's own console errors would repeat them.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  return lidar_sgm::apps::runTool(run, argc, argv);
}
