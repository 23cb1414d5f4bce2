// lidar_sgm_densify: a sparse LiDAR scan (and optionally a rectified stereo pair) in, a dense,
// colored point cloud out. The command-line face of SGMDensification.
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <pcl/console/print.h>

#include "common/arguments.hpp"
#include "common/help_layout.hpp"
#include "common/help_version.hpp"
#include "common/one_shot_allocator.hpp"
#include "common/output_paths.hpp"
#include "lidar_sgm/io/output_transaction.hpp"
#include "common/timer.hpp"
#include "common/tool_main.hpp"
#include "densify/densify_options.hpp"
#include "densify/frame_loader.hpp"
#include "densify/voxel_filter.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/cloud_preview.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/pcl_image.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

using lidar_sgm::apps::Arguments;
using lidar_sgm::apps::OutputOptions;
using lidar_sgm::apps::parseImageSize;
using lidar_sgm::apps::Timer;

namespace {

void printHelp(const char* program) {
  using lidar_sgm::apps::HelpExample;
  using lidar_sgm::apps::HelpGroup;
  const lidar_sgm::io::CloudPreviewOptions preview;
  char usage[1200];
  std::snprintf(
      usage, sizeof(usage),
      "Syntax is: %s INPUT.{pcd,bin,ply} OUTPUT.{pcd,ply} -calib CALIB [-left L.png] [-right R.png] <options>\n"
      "Densifies one LiDAR scan: fused LiDAR-SGM with a rectified stereo pair, LiDAR-only SGM without one.\n"
      "  INPUT   the LiDAR scan: KITTI velodyne .bin, or PCD/PLY with x, y, z fields (LiDAR frame, metres)\n"
      "  OUTPUT  the dense cloud, PCD or PLY (see -format): x y z, rgb when there is a left image, and the\n"
      "          per-point confidence in [0, 1] (field `confidence`; not with -no_confidence)\n",
      program);
  const std::string inputs =
      "  -calib CALIB             KITTI object calib (.txt: P2, P3, R0_rect, Tr_velo_to_cam), KITTI raw (the\n"
      "                           date folder, or its calib_cam_to_cam.txt with calib_velo_to_cam.txt beside\n"
      "                           it) or our YAML (.yaml/.yml)\n"
      "  -left L.png -right R.png rectified stereo pair: fused LiDAR-SGM (default without them: LiDAR-only)\n"
      "  -left L.png              alone: LiDAR-only SGM, the output colored from L\n"
      "  -image_size WxH          image size when neither the calibration nor an image gives it (KITTI object calib)\n" +
      lidar_sgm::apps::inputLimitOptionsHelp();
  char previewLines[1600];
  std::snprintf(
      previewLines, sizeof(previewLines),
      "  -preview OUT.png         also write a picture of the dense cloud seen from above and behind the rig\n"
      "                           (point colors, or depth colors without -left; grid every 10 m on the ground,\n"
      "                           the rig a white triangle): sky curtains and flying points stand out\n"
      "  -preview_color image|depth\n"
      "                           its colors: the points' (from -left; depth without it) or depth, blue near ...\n"
      "                           red at -max_depth (default: image)\n"
      "  -preview_size WxH        its size (default: %dx%d)\n"
      "  -preview_height M        its camera's height above the rig camera [m] (default: %g)\n"
      "  -preview_behind M        its camera's distance behind the rig camera [m] (default: %g)\n"
      "  -preview_pitch DEG       its camera looks down by DEG degrees (default: %g)\n"
      "  -preview_ground M        the ground's distance below the rig camera, for the grid [m] (default: %g)\n",
      preview.width, preview.height, preview.cameraHeight, preview.cameraBehind, preview.pitchDeg,
      preview.groundBelowCamera);
  const std::string outputs =
      lidar_sgm::apps::outputOptionsHelp() +
      "  -disparity OUT.png       also write the dense disparity (KITTI format: uint16, disparity*256, 0 = none)\n"
      "  -depth OUT.png           also write the dense depth (KITTI depth-completion format: uint16, metres*256,\n"
      "                           0 = none or beyond -max_depth)\n"
      "  -color OUT.png           also write a color-mapped picture of the disparity (invalid = black)\n"
      "  -confidence OUT.png      also write the confidence (8-bit gray: 255 x the probability that the\n"
      "                           disparity is right, 0 = none)\n" +
      previewLines;
  const std::string sample = "data/sample/";
  const std::string pair = " -left " + sample + "image_2/000000.png -right " + sample + "image_3/000000.png";
  const std::string raw = "2011_09_26/2011_09_26_drive_0005_sync/";
  const std::vector<HelpExample> examples{
      {"A KITTI object frame (the bundled sample), fused, with its disparity image and a preview:",
       "lidar_sgm_densify " + sample + "velodyne/000000.bin dense.pcd -calib " + sample + "calib/000000.txt" + pair +
           " -disparity disparity.png -preview preview.png"},
      {"LiDAR-only (no right image; colored from the left one), at half scale, as PLY:",
       "lidar_sgm_densify " + sample + "velodyne/000000.bin lidar_only.ply -calib " + sample +
           "calib/000000.txt -left " + sample + "image_2/000000.png -scale 0.5"},
      {"A KITTI raw frame: the date folder is the calibration (calib_cam_to_cam.txt, calib_velo_to_cam.txt):",
       "lidar_sgm_densify " + raw + "velodyne_points/data/0000000000.bin raw.pcd -calib 2011_09_26 -left " + raw +
           "image_02/data/0000000000.png -right " + raw + "image_03/data/0000000000.png -frame camera"},
  };
  const std::string text = lidar_sgm::apps::helpText(
      usage,
      {{"Inputs", inputs},
       {"Outputs", outputs},
       {"Method", lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Method, lidar_sgm::OptionScope::Cloud)},
       {"Speed", lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Speed, lidar_sgm::OptionScope::Cloud)},
       {"Filters", lidar_sgm::optionsHelp(lidar_sgm::OptionGroup::Filters, lidar_sgm::OptionScope::Cloud)}},
      examples);
  std::fputs(text.c_str(), stdout);
}

/// -format and -voxel (shared with lidar_sgm_batch), and OUTPUT's extension for the format,
/// checked before any file is read.
OutputOptions checkedOutputOptions(const Arguments& args) {
  const OutputOptions o = lidar_sgm::apps::outputOptionsFrom(args);
  try {
    lidar_sgm::io::checkCloudOutput(args.positionals().at(1), o.format);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -format: ") + e.what());
  }
  return o;
}

/// -preview_* (checked before any file is read); the cloud's -max_depth bounds the picture too.
lidar_sgm::io::CloudPreviewOptions previewOptionsFrom(const Arguments& args, const lidar_sgm::DensifierConfig& config) {
  lidar_sgm::io::CloudPreviewOptions o;
  if (args.has("preview_size")) parseImageSize(args.text("preview_size", ""), o.width, o.height, "preview_size");
  o.cameraHeight = args.number("preview_height", o.cameraHeight);
  o.cameraBehind = args.number("preview_behind", o.cameraBehind);
  o.pitchDeg = args.number("preview_pitch", o.pitchDeg);
  o.groundBelowCamera = args.number("preview_ground", o.groundBelowCamera);
  const std::string color = args.text("preview_color", "image");
  if (color != "image" && color != "depth") {
    throw std::invalid_argument("option -preview_color: '" + color + "' must be image or depth");
  }
  if (std::isfinite(config.reprojection.maxDepth)) o.maxDepth = config.reprojection.maxDepth;
  try {
    lidar_sgm::io::validate(o);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -preview_*: ") + e.what());
  }
  return o;
}

/// The dense cloud's points in the rig camera frame, with their colors when it has any.
template <typename PointT>
void previewPoints(const pcl::PointCloud<PointT>& dense, lidar_sgm::geometry::OutputFrame frame,
                   const lidar_sgm::geometry::StereoCalibration& calibration, std::vector<Eigen::Vector3f>& points,
                   std::vector<lidar_sgm::Rgb8>& colors) {
  Eigen::Matrix4f toCamera = Eigen::Matrix4f::Identity();
  if (frame == lidar_sgm::geometry::OutputFrame::Lidar) toCamera = calibration.T_cam_lidar.matrix().cast<float>();
  points.reserve(dense.size());
  for (const PointT& p : dense.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    points.push_back((toCamera * Eigen::Vector4f(p.x, p.y, p.z, 1.0f)).template head<3>());
    if constexpr (pcl::traits::has_color_v<PointT>) colors.push_back({p.r, p.g, p.b});
  }
}

std::size_t validPixels(const lidar_sgm::Image<std::int16_t>& disparity) {
  std::size_t valid = 0;
  for (int y = 0; y < disparity.height(); ++y) {
    for (int x = 0; x < disparity.width(); ++x) valid += disparity(x, y) != lidar_sgm::kInvalidDisparity ? 1 : 0;
  }
  return valid;
}

template <typename PointOutT>
int densify(const Arguments& args, const lidar_sgm::DensifierConfig& config, const pcl::PointCloud<pcl::PointXYZI>::Ptr& scan,
            const lidar_sgm::geometry::StereoCalibration& calibration, const cv::Mat& left, const cv::Mat& right,
            lidar_sgm::io::OutputTransaction& outputs) {
  lidar_sgm::SGMDensification<pcl::PointXYZI, PointOutT> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(calibration);
  sgm.setConfig(config);
  const lidar_sgm::Parameters& params = config.matcher;
  const OutputOptions out = checkedOutputOptions(args);
  const lidar_sgm::geometry::OutputFrame frame = config.reprojection.frame;
  // Matching sees the images' full depth (8 or 16 bit gray); the output's color is 8-bit. Both
  // come from the image decoded once.
  lidar_sgm::apps::setImages(sgm, left, right);

  pcl::PointCloud<PointOutT> dense;
  sgm.filter(dense);
  if (!sgm.getLastError().empty()) throw std::runtime_error(sgm.getLastError());
  if (dense.empty()) {
    throw std::runtime_error("the dense cloud is empty: no pixel has a disparity within -max_depth " +
                             std::to_string(config.reprojection.maxDepth) + " m");
  }
  const auto& timings = sgm.getTimings();
  const auto& stats = sgm.getProjectedLidar().stats;
  const auto& used = sgm.getDisparityImage();
  const lidar_sgm::geometry::DisparityRange& range = sgm.getUsedDisparityRange();  // what was matched
  std::printf("Projecting [done, %.0f ms : %s]\n", timings.project, stats.describe().c_str());
  std::printf("Matching (%s, alpha %g%s) [done, %.0f ms : %dx%d, %.1f %% of pixels have a disparity; filters "
              "removed %zu sky, %zu outlier pixels]\n",
              lidar_sgm::toString(sgm.getLastMode()).c_str(),
              sgm.getLastMode() == lidar_sgm::MatchMode::Fused ? params.alpha : 1.0,
              params.scale == 1.0f ? "" : ", matched at scale 0.5", timings.match, used.width(),
              used.height(), 100.0 * static_cast<double>(validPixels(used)) / (static_cast<double>(used.width()) * used.height()),
              sgm.getFilterStats().sky, sgm.getFilterStats().outliers);
  if (sgm.getLastMode() == lidar_sgm::MatchMode::Fused) {
    const auto& filters = sgm.getFilterStats();
    std::printf("LiDAR points left out of the matching: %zu hidden behind what stereo sees (its match %.0f ms), "
                "%zu contradicted by the pair\n",
                filters.hiddenLidar, timings.witness, filters.inconsistentLidar);
  }
  std::printf("disparity range: %s\n", sgm.getUsedDisparityRange().describe().c_str());
  std::printf("Reprojecting [done, %.0f ms : %zu points, %ux%u, %s frame]\n", timings.reproject, dense.size(),
              dense.width, dense.height, frame == lidar_sgm::geometry::OutputFrame::Camera ? "camera" : "lidar");
  if (out.voxel > 0.0) {
    const Timer voxelTimer;
    const std::size_t before = dense.size();
    lidar_sgm::apps::voxelDownsample(dense, out.voxel);
    std::printf("Down-sampling [done, %.0f ms : %zu -> %zu points, %g m voxels]\n", voxelTimer.elapsedMs(), before,
                dense.size(), out.voxel);
  }

  const std::string outPath = args.positionals()[1];
  const std::string disparityPath = args.text("disparity", "");
  const std::string colorPath = args.text("color", "");
  const std::string depthPath = args.text("depth", "");
  const std::string confidencePath = args.text("confidence", "");
  const std::string previewPath = args.text("preview", "");
  // Drawn before anything is written, so a failure cannot leave the cloud without its picture.
  cv::Mat preview;
  if (!previewPath.empty()) {
    Timer previewTimer;
    std::printf("Drawing the preview");
    std::fflush(stdout);
    std::vector<Eigen::Vector3f> points;
    std::vector<lidar_sgm::Rgb8> colors;
    previewPoints(dense, frame, sgm.getCalibration(), points, colors);
    if (args.text("preview_color", "image") == "depth") colors.clear();
    preview = lidar_sgm::io::renderCloudPreview(points, colors, previewOptionsFrom(args, config));
    std::printf(" [done, %.1f ms : %zu points, %dx%d]\n", previewTimer.elapsedMs(), points.size(), preview.cols,
                preview.rows);
  }
  Timer saveTimer;
  std::printf("Saving %s (%s)", outPath.c_str(), lidar_sgm::io::toString(out.format).c_str());
  std::fflush(stdout);
  // Every output goes to its temporary; all are renamed into place once every one is written.
  outputs.write(outPath,
                [&](const std::string& temporary) { lidar_sgm::io::writeCloud(temporary, dense, out.format); });
  if (!disparityPath.empty()) {
    std::printf(", %s", disparityPath.c_str());
    outputs.write(disparityPath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::toKittiDisparity(used.view()));
    });
  }
  if (!depthPath.empty()) {
    std::printf(", %s", depthPath.c_str());
    outputs.write(depthPath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::toKittiDepth(sgm.getDepthImage().view()));
    });
  }
  if (!confidencePath.empty()) {
    std::printf(", %s", confidencePath.c_str());
    outputs.write(confidencePath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(temporary, lidar_sgm::io::toConfidencePng(sgm.getConfidenceImage().view()));
    });
  }
  if (!colorPath.empty()) {
    std::printf(", %s", colorPath.c_str());
    outputs.write(colorPath, [&](const std::string& temporary) {
      lidar_sgm::io::writeImageAtomically(
          temporary, lidar_sgm::io::colorizeDisparity(used.view(), range.minDisparity + range.numDisparities));
    });
  }
  if (!previewPath.empty()) {
    std::printf(", %s", previewPath.c_str());
    outputs.write(previewPath,
                  [&](const std::string& temporary) { lidar_sgm::io::writeImageAtomically(temporary, preview); });
  }
  outputs.commit();
  std::printf(" [done, %.0f ms]\n", saveTimer.elapsedMs());
  return 0;
}

int run(int argc, char** argv) {
  using lidar_sgm::apps::joined;
  const Arguments args(argc, argv,
                       joined(lidar_sgm::apps::densifyValueOptions(),
                              {"calib", "left", "right", "disparity", "depth", "color", "confidence", "preview",
                               "preview_color", "preview_size", "preview_height", "preview_behind", "preview_pitch",
                               "preview_ground"}),
                       lidar_sgm::apps::densifyFlagOptions());
  if (lidar_sgm::apps::answerHelpOrVersion(args, "lidar_sgm_densify", [&] { printHelp(argv[0]); })) {
    if (args.versionRequested()) std::printf("allocator: %s\n", lidar_sgm::apps::allocatorDescription().c_str());
    return 0;
  }
  const std::vector<std::string>& files = args.positionals();
  if (files.size() != 2) {
    throw std::invalid_argument("expected INPUT and OUTPUT, got " + std::to_string(files.size()) +
                                " file name(s) (see -h)");
  }
  const std::string inputPath = files[0];
  const std::string outPath = files[1];
  const std::string calibPath = args.text("calib", "");
  const std::string leftPath = args.text("left", "");
  const std::string rightPath = args.text("right", "");
  if (calibPath.empty()) throw std::invalid_argument("-calib CALIB is required (KITTI object/raw calib or YAML)");
  if (!rightPath.empty() && leftPath.empty()) throw std::invalid_argument("-right needs -left");
  // Every output is checked before any work: extension, not an input, not another output.
  const std::vector<std::string> inputs{inputPath, calibPath, leftPath, rightPath};
  lidar_sgm::apps::requireOutput(outPath, {".pcd", ".ply"}, inputs);
  std::vector<std::string> outputs{outPath};  // every file this run writes
  if (args.has("confidence") && args.has("no_confidence")) {
    throw std::invalid_argument("-confidence OUT.png needs the confidence, which -no_confidence turns off");
  }
  for (const char* option : {"disparity", "depth", "color", "confidence", "preview"}) {
    const std::string path = args.text(option, "");
    if (path.empty()) continue;
    lidar_sgm::apps::requireOutput(path, {".png"}, inputs);
    for (const std::string& other : outputs) {
      if (lidar_sgm::apps::samePath(path, other)) {
        throw std::invalid_argument(std::string("-") + option + " '" + path + "' is also another output");
      }
    }
    outputs.push_back(path);
  }
  // Bad options are refused before anything is loaded.
  const lidar_sgm::DensifierConfig config = lidar_sgm::apps::checkedDensifyOptions(args);
  checkedOutputOptions(args);
  previewOptionsFrom(args, config);
  int width = 0;
  int height = 0;
  if (args.has("image_size")) parseImageSize(args.text("image_size", ""), width, height);
  // Folders and permissions checked now, before any work; nothing replaced until all are written.
  lidar_sgm::io::OutputTransaction transaction(outputs);

  lidar_sgm::apps::FrameFiles frameFiles;
  frameFiles.scan = inputPath;
  frameFiles.calib = calibPath;
  frameFiles.left = leftPath;
  frameFiles.right = rightPath;
  frameFiles.width = width;
  frameFiles.height = height;
  frameFiles.maxPoints = lidar_sgm::apps::maxPointsFrom(args);
  const lidar_sgm::apps::LoadedFrame loaded = lidar_sgm::apps::loadFrame(frameFiles, stdout);
  const pcl::PointCloud<pcl::PointXYZI>::Ptr& scan = loaded.scan;
  const lidar_sgm::geometry::StereoCalibration& calibration = loaded.calibration;
  const cv::Mat& left = loaded.left;
  const cv::Mat& right = loaded.right;
  // Colored output when an image can color it; with the confidence field unless it is off.
  if (args.has("no_confidence")) {
    return left.empty() ? densify<pcl::PointXYZ>(args, config, scan, calibration, left, right, transaction)
                        : densify<pcl::PointXYZRGB>(args, config, scan, calibration, left, right, transaction);
  }
  return left.empty() ? densify<lidar_sgm::PointXYZConfidence>(args, config, scan, calibration, left, right, transaction)
                      : densify<lidar_sgm::PointXYZRGBConfidence>(args, config, scan, calibration, left, right, transaction);
}

}  // namespace

int main(int argc, char** argv) {
  // Our messages name the problem; PCL's own console errors would repeat them.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  return lidar_sgm::apps::runTool(run, argc, argv);
}
