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
#include "common/help_version.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"

namespace fs = std::filesystem;
using lidar_sgm::apps::Arguments;
using lidar_sgm::apps::Timer;
namespace synth = lidar_sgm::synth;

namespace {

const synth::FrameOptions kDefaults;

void printHelp(const char* program) {
  std::printf(
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
      "where options are:\n"
      "  -out DIR              output directory (created if missing)\n"
      "  -n N                  number of frames, >= 1 (default: 1)\n"
      "  -seed S               seed of the first frame, >= 0 (default: %u)\n"
      "  -weather clear|rain   rain: fog, low contrast, wet road, noise, streaks; images only (default: clear)\n"
      "  -beams 64|128         64: HDL-64E (+2..-24.8 deg, 120 m); 128: +15..-25 deg, 245 m (default: %d)\n"
      "  -third_camera         also render a camera 0.20 m above the left one (image_up/, P_up)\n"
      "  -baseline B           stereo baseline [m], in [0.05, 2] (default: %g)\n"
      "  -width W -height H    image size [px]; KITTI intrinsics scaled to it (default: %dx%d)\n"
      "  -lidar_in_camera_view keep only the LiDAR points that project into the left image\n"
      "  -h, --help            this help\n"
      "  --version             the tool's name and version\n"
      "Every option also takes the GNU spelling: --out DIR, --out=DIR.\n",
      program, kDefaults.seed, kDefaults.beams, kDefaults.baseline, kDefaults.width, kDefaults.height);
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

// Same pattern as io::writeImageAtomically: temporary file in the target's directory, then rename.
void writeFileAtomically(const fs::path& target, const std::string& bytes) {
  fs::path temporary = target;
  temporary.replace_filename("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) +
                             target.extension().string());
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw std::runtime_error("cannot write '" + target.string() + "'");
    }
  }
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + target.string() + "': " + ec.message());
  }
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

int run(int argc, char** argv) {
  const Arguments args(argc, argv, {"out", "n", "seed", "weather", "beams", "baseline", "width", "height"},
                       {"third_camera", "lidar_in_camera_view"});
  if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_synth", [&] { printHelp(argv[0]); })) return 0;
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  const std::string outText = args.text("out", "");
  if (outText.empty()) throw std::invalid_argument("option -out DIR is required (see -h)");
  const int count = args.integer("n", 1);
  if (count < 1) throw std::invalid_argument("option -n: " + std::to_string(count) + " must be >= 1");
  const int seed = args.integer("seed", static_cast<int>(kDefaults.seed));
  if (seed < 0) throw std::invalid_argument("option -seed: " + std::to_string(seed) + " must be >= 0");
  synth::FrameOptions options;
  options.weather = synth::weatherFromString(args.text("weather", "clear"));
  options.beams = args.integer("beams", kDefaults.beams);
  options.thirdCamera = args.has("third_camera");
  options.baseline = args.number("baseline", kDefaults.baseline);
  options.width = args.integer("width", kDefaults.width);
  options.height = args.integer("height", kDefaults.height);
  options.lidarInCameraViewOnly = args.has("lidar_in_camera_view");
  synth::validate(options);  // before anything is created: a rejected call leaves nothing behind

  const fs::path out(outText);
  std::vector<std::string> folders{"image_2", "image_3", "velodyne", "calib", "disp_gt", "depth_gt", "mask",
                                   "lidar_disp"};
  if (options.thirdCamera) folders.push_back("image_up");
  for (const std::string& folder : folders) fs::create_directories(out / folder);

  for (int i = 0; i < count; ++i) {
    char id[16];
    std::snprintf(id, sizeof(id), "%06d", i);
    options.seed = static_cast<std::uint32_t>(seed) + static_cast<std::uint32_t>(i);
    Timer timer;
    std::printf("Rendering %s (seed %u, %s, %d beams)", id, options.seed, synth::toString(options.weather).c_str(),
                options.beams);
    std::fflush(stdout);
    const synth::Frame frame = synth::renderFrame(options);
    std::printf(" [done, %.0f ms : %dx%d, %zu LiDAR points]", timer.elapsedMs(), options.width, options.height,
                frame.lidar.size());
    Timer saveTimer;
    writeFrame(out, id, frame, options.thirdCamera);
    std::printf(", saved [done, %.0f ms]\n", saveTimer.elapsedMs());
  }
  std::printf("Wrote %d frame(s) to %s\n", count, out.string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return lidar_sgm::apps::runTool(run, argc, argv);
}
