// lidar_sgm_disparity: LiDAR-SGM on one frame, images in, KITTI disparity PNG out.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/arguments.hpp"
#include "common/config_arguments.hpp"
#include "common/help_layout.hpp"
#include "common/help_version.hpp"
#include "common/one_shot_allocator.hpp"
#include "common/output_paths.hpp"
#include "lidar_sgm/io/output_transaction.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/sparse_lidar_check.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace fs = std::filesystem;
using lidar_sgm::apps::Arguments;
using lidar_sgm::apps::Timer;
using lidar_sgm::optionsHelp;
using lidar_sgm::apps::joined;
using lidar_sgm::apps::samePath;
using lidar_sgm::OptionGroup;
using lidar_sgm::OptionScope;

namespace {

void printHelp(const char* program) {
  char usage[800];
  std::snprintf(usage, sizeof(usage),
                "Syntax is: %s LEFT.png [RIGHT.png] OUT.png <options>\n"
                "  LEFT OUT        LiDAR-only SGM (needs -lidar or -lidar_depth; LEFT gives the image size)\n"
                "  LEFT RIGHT OUT  stereo-only SGM, or fused LiDAR-SGM with -lidar / -lidar_depth\n"
                "  OUT.png is written in KITTI disparity format (uint16, disparity*256, 0 = invalid).\n"
                "  Images: gray or color, 8 or 16 bit.\n",
                program);
  const std::string inputs =
      "  -lidar SPARSE.png        sparse LiDAR disparity, KITTI format (uint16, disparity*256, 0 = none)\n"
      "  -lidar_depth DEPTH.png   sparse LiDAR depth, KITTI depth format (uint16, metres*256, 0 = none)\n"
      "  -fb F                    focal length [px] * baseline [m] for -lidar_depth (d = F/z)\n";
  const std::string outputs =
      "  -color OUT_COLOR.png     also write a color-mapped picture of the disparity (invalid = black)\n"
      "  -confidence OUT_CONF.png also write the confidence (8-bit gray: 255 x the probability that the\n"
      "                           disparity is right, 0 = none)\n";
  const std::string left = "data/sample/image_2/000000.png";
  const std::string right = "data/sample/image_3/000000.png";
  const std::string lidar = "data/sample/lidar_disp/000000.png";
  const std::vector<lidar_sgm::apps::HelpExample> examples{
      {"Stereo-only SGM on the sample's pair, with a color picture of the result:",
       "lidar_sgm_disparity " + left + " " + right + " stereo.png -color stereo_color.png"},
      {"Fused LiDAR-SGM with the scan's sparse disparity (KITTI format), and its confidence:",
       "lidar_sgm_disparity " + left + " " + right + " fused.png -lidar " + lidar + " -confidence confidence.png"},
      {"LiDAR-only SGM at half scale (the left image gives the size):",
       "lidar_sgm_disparity " + left + " lidar_only.png -lidar " + lidar + " -scale 0.5"},
  };
  const std::string text = lidar_sgm::apps::helpText(usage,
                                                     {{"Inputs", inputs},
                                                      {"Outputs", outputs},
                                                      {"Method", optionsHelp(OptionGroup::Method, OptionScope::Disparity)},
                                                      {"Speed", optionsHelp(OptionGroup::Speed, OptionScope::Disparity)},
                                                      {"Filters", optionsHelp(OptionGroup::Filters, OptionScope::Disparity)}},
                                                     examples);
  std::fputs(text.c_str(), stdout);
}

void requirePngOutput(const std::string& path, const std::vector<std::string>& inputs) {
  lidar_sgm::apps::requireOutput(path, {".png"}, inputs);
}

int run(int argc, char** argv) {
  const Arguments args(argc, argv,
                       joined(lidar_sgm::apps::configValueOptions(OptionScope::Disparity),
                              {"lidar", "lidar_depth", "fb", "color", "confidence"}),
                       lidar_sgm::apps::configFlagOptions(OptionScope::Disparity));
  if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_disparity", [&] { printHelp(argv[0]); })) {
    if (args.versionRequested()) std::printf("allocator: %s\n", lidar_sgm::apps::allocatorDescription().c_str());
    return 0;
  }
  const std::vector<std::string>& files = args.positionals();
  if (files.size() != 2 && files.size() != 3) {
    throw std::invalid_argument("expected LEFT.png [RIGHT.png] OUT.png, got " + std::to_string(files.size()) +
                                " file name(s) (see -h)");
  }
  const bool stereo = files.size() == 3;
  const std::string leftPath = files[0];
  const std::string rightPath = stereo ? files[1] : "";
  const std::string outPath = files.back();
  const std::string lidarPath = args.text("lidar", "");
  const std::string depthPath = args.text("lidar_depth", "");
  const std::string colorPath = args.text("color", "");
  const std::string confidencePath = args.text("confidence", "");
  if (!lidarPath.empty() && !depthPath.empty()) {
    throw std::invalid_argument("give either -lidar or -lidar_depth, not both");
  }
  if (!depthPath.empty() && !args.has("fb")) {
    throw std::invalid_argument("-lidar_depth needs -fb (focal length [px] * baseline [m])");
  }
  if (!stereo && lidarPath.empty() && depthPath.empty()) {
    throw std::invalid_argument("LiDAR-only mode (LEFT OUT) needs -lidar or -lidar_depth");
  }
  std::vector<std::string> inputs{leftPath};
  for (const std::string& p : {rightPath, lidarPath, depthPath}) {
    if (!p.empty()) inputs.push_back(p);
  }
  requirePngOutput(outPath, inputs);
  if (!colorPath.empty()) {
    requirePngOutput(colorPath, inputs);
    if (samePath(colorPath, outPath)) throw std::invalid_argument("-color must differ from OUT.png");
  }
  if (!confidencePath.empty()) {
    if (args.has("no_confidence")) {
      throw std::invalid_argument("-confidence OUT_CONF.png needs the confidence, which -no_confidence turns off");
    }
    requirePngOutput(confidencePath, inputs);
    if (samePath(confidencePath, outPath) || (!colorPath.empty() && samePath(confidencePath, colorPath))) {
      throw std::invalid_argument("-confidence must differ from OUT.png and -color");
    }
  }
  // This tool stops at the disparity (no calibration, no cloud).
  lidar_sgm::DensifierConfig config = lidar_sgm::apps::configFrom(args, OptionScope::Disparity);
  config.computeCloud = false;
  const lidar_sgm::Parameters& params = config.matcher;
  // Folders and permissions checked now, before any work; nothing replaced until all are written.
  std::vector<std::string> outputPaths{outPath};
  if (!colorPath.empty()) outputPaths.push_back(colorPath);
  if (!confidencePath.empty()) outputPaths.push_back(confidencePath);
  lidar_sgm::io::OutputTransaction outputs(outputPaths);

  Timer loadTimer;
  std::printf("Loading %s", leftPath.c_str());
  const cv::Mat left = lidar_sgm::io::readGrayImage(leftPath);
  cv::Mat right;
  if (stereo) {
    std::printf(", %s", rightPath.c_str());
    right = lidar_sgm::io::readGrayImage(rightPath);
  }
  lidar_sgm::Image<std::int16_t> sparse;
  if (!lidarPath.empty()) {
    std::printf(", %s", lidarPath.c_str());
    sparse = lidar_sgm::io::readKittiDisparity(lidarPath);
  } else if (!depthPath.empty()) {
    std::printf(", %s", depthPath.c_str());
    sparse = lidar_sgm::io::readKittiDepthAsDisparity(depthPath, args.number("fb", 0.0));
  }
  lidar_sgm::LidarPoints lidar;
  if (!sparse.empty()) lidar = lidar_sgm::LidarPoints::fromDisparityImage(sparse.view());
  std::printf(" [done, %.0f ms : %dx%d, %zu LiDAR points]\n", loadTimer.elapsedMs(), left.cols, left.rows,
              lidar.size());
  if (!sparse.empty() && lidar.empty()) {
    throw std::invalid_argument("the LiDAR image '" + (lidarPath.empty() ? depthPath : lidarPath) +
                                "' holds no valid point");
  }
  if (!sparse.empty()) {
    // Disparity and depth PNGs share KITTI's format: the values say which one this is.
    const lidar_sgm::io::SparseLidarCheck check = lidarPath.empty()
                                                      ? lidar_sgm::io::checkSparseDepth(depthPath, sparse.view())
                                                      : lidar_sgm::io::checkSparseDisparity(lidarPath, sparse.view(), left.cols);
    if (!check.error.empty()) throw std::invalid_argument(check.error);
    for (const std::string& warning : check.warnings) std::fprintf(stderr, "Warning: %s\n", warning.c_str());
  }

  // The pipeline every tool runs.
  lidar_sgm::Densifier densifier;
  densifier.setConfig(config);
  if (stereo) densifier.setStereoPair(lidar_sgm::io::grayView(left), lidar_sgm::io::grayView(right));
  Timer sgmTimer;
  const bool lidarOnly = !stereo;
  if (lidarOnly && (left.cols != lidar.width() || left.rows != lidar.height())) {
    throw std::invalid_argument("the LiDAR image is " + std::to_string(lidar.width()) + "x" +
                                std::to_string(lidar.height()) + " but LEFT is " + std::to_string(left.cols) + "x" +
                                std::to_string(left.rows));
  }
  densifier.runProjected(lidar.empty() ? nullptr : &lidar);
  const lidar_sgm::Image<std::int16_t>& disparity = densifier.disparity();
  std::printf("Matching (%s, %s, alpha %g%s) [done, %.0f ms : %.1f %% of pixels have a disparity]\n",
              lidar_sgm::toString(densifier.lastMode()).c_str(), lidar_sgm::toString(densifier.usedBackend()).c_str(),
              densifier.lastMode() == lidar_sgm::MatchMode::Fused ? params.alpha
              : densifier.lastMode() == lidar_sgm::MatchMode::LidarOnly ? 1.0 : 0.0,
              params.scale == 1.0f ? "" : ", matched at scale 0.5", sgmTimer.elapsedMs(), densifier.validPercent());
  std::printf("disparity range: %s\n", densifier.usedDisparityRange().describe().c_str());

  Timer saveTimer;
  std::printf("Saving %s", outPath.c_str());
  // Every output goes to its temporary; all are renamed into place once every one is written.
  outputs.write(outPath, [&](const std::string& temporary) {
    lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::toKittiDisparity(disparity.view()));
  });
  if (!colorPath.empty()) {
    std::printf(", %s", colorPath.c_str());
    const lidar_sgm::Parameters& used = densifier.usedParameters();  // the range matched, e.g. from the LiDAR
    const double maxDisparity = used.minDisparity + used.numDisparities;
    outputs.write(colorPath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::colorizeDisparity(disparity.view(), maxDisparity));
    });
  }
  if (!confidencePath.empty()) {
    std::printf(", %s", confidencePath.c_str());
    outputs.write(confidencePath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::toConfidencePng(densifier.confidence().view()));
    });
  }
  outputs.commit();
  std::printf(" [done, %.0f ms]\n", saveTimer.elapsedMs());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return lidar_sgm::apps::runTool(run, argc, argv);
}
