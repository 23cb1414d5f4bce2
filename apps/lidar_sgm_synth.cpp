// lidar_sgm_synth: synthetic street frames with exact ground truth, written in KITTI's layout.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/arguments.hpp"
#include "common/help_layout.hpp"
#include "common/help_version.hpp"
#include "common/output_paths.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"
#include "lidar_sgm/synth/sequence.hpp"

namespace fs = std::filesystem;
using lidar_sgm::apps::Arguments;
using lidar_sgm::apps::Timer;
namespace synth = lidar_sgm::synth;

namespace {

const synth::FrameOptions kDefaults;
const synth::SequenceOptions kSequenceDefaults;

void printHelp(const char* program) {
  char usage[2400];
  std::snprintf(
      usage, sizeof(usage),
      "Syntax is: %s -out DIR <options>\n"
      "  Renders N synthetic street frames (stereo pair, LiDAR sweep, exact ground truth) into DIR:\n"
      "    image_2/ image_3/ [image_up/]  left, right [, third] color images (PNG)\n"
      "    velodyne/  KITTI .bin (float32 x y z intensity, LiDAR frame; front half only)\n"
      "    calib/     KITTI object calibration (P2 left, P3 right, Tr_velo_to_cam [, P_up])\n"
      "    disp_gt/   left disparity, KITTI format (uint16, disparity*256, 0 = none/sky)\n"
      "    lidar_disp/ the scan projected into the left image, KITTI disparity format (0 = no point)\n"
      "    depth_gt/  left depth, KITTI depth format (uint16, metres*256, 0 = none/sky)\n"
      "    mask/      objects (cars, poles, signs, trees) = 1, else 0 (uint8)\n"
      "  Frame i (id %%06d) is rendered with seed S+i; the same seed gives the same files.\n"
      "  With -sequence N: N frames of one drive along the street of seed S, as a KITTI odometry\n"
      "  sequence: the folders above (velodyne/ and image_2/ in the rig's frame at each step) and\n"
      "    calib.txt  KITTI odometry calibration (P0 = P2 left, P1 = P3 right, Tr: LiDAR to camera 0)\n"
      "    poses.txt  KITTI odometry poses: line i = 3x4 row-major, left camera i to left camera 0\n"
      "    times.txt  frame times [s], 0.1 s apart\n"
      "  The car drives straight along the street; the world is static, so the GT is exact in every frame.\n",
      program);
  const std::string outputs =
      "  -out DIR              output directory (created if missing)\n"
      "  -n N                  number of independent frames, >= 1 (default: 1)\n"
      "  -sequence N           number of frames of one drive, in [1, 100000]; not with -n\n";
  char scene[1600];
  std::snprintf(
      scene, sizeof(scene),
      "  -step S               metres driven between frames of -sequence, in (0, 5] (default: %g, ~29 km/h at 10 Hz)\n"
      "  -seed S               seed of the first frame (of the street with -sequence), >= 0 (default: %u)\n"
      "  -weather clear|rain   rain: fog, low contrast, wet road, noise, streaks; images only (default: clear)\n",
      kSequenceDefaults.step, kDefaults.seed);
  char sensors[1600];
  std::snprintf(
      sensors, sizeof(sensors),
      "  -beams 64|128         64: HDL-64E (+2..-24.8 deg, 120 m); 128: +15..-25 deg, 245 m (default: %d)\n"
      "  -third_camera         also render a camera 0.20 m above the left one (image_up/, P_up)\n"
      "  -baseline B           stereo baseline [m], in [0.05, 2] (default: %g)\n"
      "  -width W -height H    image size [px]; KITTI intrinsics scaled to it (default: %dx%d)\n"
      "  -lidar_in_camera_view keep only the LiDAR points that project into the left image\n",
      kDefaults.beams, kDefaults.baseline, kDefaults.width, kDefaults.height);
  const std::vector<lidar_sgm::apps::HelpExample> examples{
      {"Two independent frames in KITTI's object layout (then: lidar_sgm_batch -input_dir frames ...):",
       "lidar_sgm_synth -out frames -n 2"},
      {"A drive of 3 frames, 1 m apart, as a KITTI odometry sequence (for lidar_sgm_batch and its map):",
       "lidar_sgm_synth -out drive -sequence 3 -step 1"},
      {"A rainy frame seen by a 128-beam LiDAR, at half KITTI's size:",
       "lidar_sgm_synth -out rain -weather rain -beams 128 -width 621 -height 188"},
  };
  const std::string text = lidar_sgm::apps::helpText(
      usage, {{"Outputs", outputs}, {"Scene", scene}, {"Sensors", sensors}}, examples);
  std::fputs(text.c_str(), stdout);
}

cv::Mat toMat(const lidar_sgm::Image<lidar_sgm::Rgb8>& image) {
  cv::Mat bgr(image.height(), image.width(), CV_8UC3);
  for (int y = 0; y < image.height(); ++y) {
    auto* row = bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.width(); ++x) {
      const lidar_sgm::Rgb8& p = image(x, y);
      row[x] = cv::Vec3b(p.b, p.g, p.r);
    }
  }
  return bgr;
}

template <typename T>
cv::Mat toMat(const lidar_sgm::Image<T>& image, int type) {
  return cv::Mat(image.height(), image.width(), type, const_cast<T*>(image.data())).clone();
}

void writeFileAtomically(const fs::path& target, const std::string& bytes) {
  lidar_sgm::io::writeFileAtomically(target.string(), bytes);
}

std::string frameId(int index) {
  char id[16];
  std::snprintf(id, sizeof(id), "%06d", index);
  return id;
}

void writeFrame(const fs::path& out, const std::string& id, const synth::Frame& frame, bool thirdCamera) {
  using lidar_sgm::io::writeImageAtomically;
  writeImageAtomically((out / "image_2" / (id + ".png")).string(), toMat(frame.left));
  writeImageAtomically((out / "image_3" / (id + ".png")).string(), toMat(frame.right));
  if (thirdCamera) writeImageAtomically((out / "image_up" / (id + ".png")).string(), toMat(frame.up));
  writeFileAtomically(out / "velodyne" / (id + ".bin"), synth::velodyneBytes(frame.lidar));
  writeFileAtomically(out / "calib" / (id + ".txt"), synth::kittiCalibrationText(frame.rig, thirdCamera));
  writeImageAtomically((out / "disp_gt" / (id + ".png")).string(),
                       toMat(synth::encodeKittiDisparity(frame.disparity.view()), CV_16UC1));
  writeImageAtomically((out / "depth_gt" / (id + ".png")).string(),
                       toMat(synth::encodeKittiDepth(frame.depth.view()), CV_16UC1));
  writeImageAtomically((out / "mask" / (id + ".png")).string(), toMat(frame.objectMask, CV_8UC1));
  const lidar_sgm::Image<float> lidarDisparity = synth::projectLidarDisparity(frame.lidar, frame.rig);
  writeImageAtomically((out / "lidar_disp" / (id + ".png")).string(),
                       toMat(synth::encodeKittiDisparity(lidarDisparity.view()), CV_16UC1));
}

synth::FrameOptions frameOptions(const Arguments& args) {
  synth::FrameOptions options;
  options.weather = synth::weatherFromString(args.text("weather", "clear"));
  options.beams = args.integer("beams", kDefaults.beams);
  options.thirdCamera = args.has("third_camera");
  options.baseline = args.number("baseline", kDefaults.baseline);
  options.width = args.integer("width", kDefaults.width);
  options.height = args.integer("height", kDefaults.height);
  options.lidarInCameraViewOnly = args.has("lidar_in_camera_view");
  return options;
}

void createFolders(const fs::path& out, bool thirdCamera) {
  std::vector<std::string> folders{"image_2", "image_3", "velodyne", "calib", "disp_gt", "depth_gt", "mask",
                                   "lidar_disp"};
  if (thirdCamera) folders.push_back("image_up");
  for (const std::string& folder : folders) fs::create_directories(out / folder);
}

void renderFrames(const fs::path& out, synth::FrameOptions options, int count, int seed) {
  for (int i = 0; i < count; ++i) {
    const std::string id = frameId(i);
    options.seed = static_cast<std::uint32_t>(seed) + static_cast<std::uint32_t>(i);
    Timer timer;
    std::printf("Rendering %s (seed %u, %s, %d beams)", id.c_str(), options.seed,
                synth::toString(options.weather).c_str(), options.beams);
    std::fflush(stdout);
    const synth::Frame frame = synth::renderFrame(options);
    std::printf(" [done, %.0f ms : %dx%d, %zu LiDAR points]", timer.elapsedMs(), options.width, options.height,
                frame.lidar.size());
    Timer saveTimer;
    writeFrame(out, id, frame, options.thirdCamera);
    std::printf(", saved [done, %.0f ms]\n", saveTimer.elapsedMs());
  }
  std::printf("Wrote %d frame(s) to %s\n", count, out.string().c_str());
}

// One street, built once; the sequence files first, so that a folder with frames always has them.
void renderSequence(const fs::path& out, const synth::SequenceOptions& options) {
  const synth::StereoRig rig =
      synth::StereoRig::kittiLike(options.frame.width, options.frame.height, options.frame.baseline);
  writeFileAtomically(out / "calib.txt", synth::kittiOdometryCalibrationText(rig, options.frame.thirdCamera));
  writeFileAtomically(out / "poses.txt", synth::kittiPosesText(options));
  writeFileAtomically(out / "times.txt", synth::kittiTimesText(options));
  Timer sceneTimer;
  std::printf("Building the street (seed %u, %.1f m drive)", options.frame.seed, (options.frames - 1) * options.step);
  std::fflush(stdout);
  const synth::Scene scene = synth::makeSequenceScene(options);
  std::printf(" [done, %.1f ms : %zu primitives]\n", sceneTimer.elapsedMs(), scene.primitives().size());
  Timer total;
  for (int i = 0; i < options.frames; ++i) {
    const std::string id = frameId(i);
    Timer timer;
    std::printf("Rendering %s (x = %.2f m, %s, %d beams)", id.c_str(), i * options.step,
                synth::toString(options.frame.weather).c_str(), options.frame.beams);
    std::fflush(stdout);
    const synth::Frame frame = synth::renderSequenceFrame(scene, options, i);
    std::printf(" [done, %.0f ms : %dx%d, %zu LiDAR points]", timer.elapsedMs(), options.frame.width,
                options.frame.height, frame.lidar.size());
    Timer saveTimer;
    writeFrame(out, id, frame, options.frame.thirdCamera);
    std::printf(", saved [done, %.0f ms]\n", saveTimer.elapsedMs());
  }
  std::printf("Wrote a %d-frame sequence to %s [%.0f ms a frame]\n", options.frames, out.string().c_str(),
              total.elapsedMs() / options.frames);
}

int run(int argc, char** argv) {
  const Arguments args(argc, argv,
                       {"out", "n", "sequence", "step", "seed", "weather", "beams", "baseline", "width", "height"},
                       {"third_camera", "lidar_in_camera_view"});
  if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_synth", [&] { printHelp(argv[0]); })) return 0;
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  const std::string outText = args.text("out", "");
  if (outText.empty()) throw std::invalid_argument("option -out DIR is required (see -h)");
  const bool sequence = args.has("sequence");
  if (sequence && args.has("n")) {
    throw std::invalid_argument("options -sequence and -n exclude each other: -n N renders N independent streets, "
                                "-sequence N one drive of N frames");
  }
  if (!sequence && args.has("step")) throw std::invalid_argument("option -step needs -sequence N");
  const int seed = args.integer("seed", static_cast<int>(kDefaults.seed));
  if (seed < 0) throw std::invalid_argument("option -seed: " + std::to_string(seed) + " must be >= 0");
  const synth::FrameOptions options = frameOptions(args);
  synth::validate(options);  // before anything is created: a rejected call leaves nothing behind
  const fs::path out(outText);
  if (sequence) {
    synth::SequenceOptions drive;
    drive.frame = options;
    drive.frame.seed = static_cast<std::uint32_t>(seed);
    drive.frames = args.integer("sequence", 0);
    if (drive.frames < 1) {
      throw std::invalid_argument("option -sequence: " + std::to_string(drive.frames) + " must be >= 1");
    }
    drive.step = args.number("step", kSequenceDefaults.step);
    try {
      synth::validate(drive);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("option -sequence/-step: ") + e.what());
    }
    createFolders(out, options.thirdCamera);
    renderSequence(out, drive);
    return 0;
  }
  const int count = args.integer("n", 1);
  if (count < 1) throw std::invalid_argument("option -n: " + std::to_string(count) + " must be >= 1");
  createFolders(out, options.thirdCamera);
  renderFrames(out, options, count, seed);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return lidar_sgm::apps::runTool(run, argc, argv);
}
