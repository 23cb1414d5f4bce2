#include "bench_whole_frame.hpp"

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "bench_system.hpp"
#include "bench_timing.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace bench {
namespace {

const char* kFolder = "kitti2015_lidar";

Image<std::uint8_t> grayImage(const cv::Mat& gray, const std::string& path) {
  if (gray.type() != CV_8UC1) {
    throw std::runtime_error(path + ": the bench times 8-bit images (OpenCV's SGBM takes no 16-bit ones)");
  }
  Image<std::uint8_t> out(gray.cols, gray.rows);
  for (int y = 0; y < gray.rows; ++y) std::memcpy(out.view().row(y), gray.ptr<std::uint8_t>(y), out.width());
  return out;
}

Image<Rgb8> colorImage(const cv::Mat& bgr) {
  Image<Rgb8> out(bgr.cols, bgr.rows);
  for (int y = 0; y < bgr.rows; ++y) {
    const auto* row = bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgr.cols; ++x) out(x, y) = Rgb8{row[x][2], row[x][1], row[x][0]};
  }
  return out;
}

}  // namespace

WholeFrame loadKitti2015LidarFrame(const std::string& dataRoot, const std::string& id) {
  const std::filesystem::path folder = std::filesystem::path(dataRoot) / kFolder;
  if (!std::filesystem::is_directory(folder)) {
    throw std::runtime_error("no " + std::string(kFolder) + " under " + dataRoot + " (give -data ROOT)");
  }
  const std::string name = id.find('_') == std::string::npos ? id + "_10" : id;
  const std::string scan = (folder / "velodyne" / (name + ".bin")).string();
  const std::string left = (folder / "image_2" / (name + ".png")).string();
  const std::string right = (folder / "image_3" / (name + ".png")).string();
  const std::string calib = (folder / "calib" / "calib_cam_to_cam.txt").string();
  WholeFrame frame;
  // As lidar_sgm_densify: each image decoded once, then gray for matching and color for the cloud.
  const cv::Mat leftImage = io::readImage(left);
  frame.pair.left = grayImage(io::toGray(leftImage), left);
  frame.pair.right = grayImage(io::readGrayImage(right), right);
  frame.color = colorImage(io::toColor(leftImage));
  frame.calibration = io::readCalibration(calib, frame.pair.width(), frame.pair.height());
  for (const io::KittiPoint& p : io::readKittiScan(scan)) frame.points.emplace_back(p.x, p.y, p.z);
  frame.pair.source = "KITTI 2015 training " + name + " with its raw Velodyne scan (" +
                      std::to_string(frame.points.size()) + " points)";
  frame.pair.files = {{"left", left}, {"right", right}, {"scan", scan}, {"calib", calib}};
  return frame;
}

WholeFrameMeasurement measureWholeFrame(const WholeFrame& frame, Backend backend, const Parameters& matcher, float scale,
                                        const Frame& sgbmPair, const SgbmSettings& sgbm, int runs, int warmups,
                                        int idleMs, bool hiddenLidar, float witnessScale, bool lidarAnchor) {
  Densifier densifier;  // the tools' defaults: DensifierConfig as constructed
  DensifierConfig config = densifier.config();
  config.hiddenLidar.enabled = hiddenLidar;
  config.hiddenLidar.witnessScale = witnessScale;
  config.lidarAnchor.enabled = lidarAnchor;
  densifier.setConfig(config);
  densifier.setBackend(backend);
  const int threads = matcher.threads;
  densifier.parameters().threads = threads;
  densifier.parameters().gatedSearch = matcher.gatedSearch;
  densifier.parameters().gatedSearchMargin = matcher.gatedSearchMargin;
  densifier.parameters().gatedSearchRows = matcher.gatedSearchRows;
  densifier.parameters().scale = scale;
  densifier.setCalibration(frame.calibration);
  densifier.setStereoPair(frame.pair.left.view(), frame.pair.right.view());
  densifier.setColorImage(frame.color.view());

  std::vector<double> project, match, reproject, kernel, confidence, witness, filters;
  int frames = 0;
  const auto oneFrame = [&] {
    densifier.run(frame.points);
    if (densifier.lastMode() != MatchMode::Fused) {
      throw std::logic_error("the Densifier ran " + toString(densifier.lastMode()) + ", not fused");
    }
    if (frames++ < warmups) return;
    const DensificationTimings& t = densifier.timings();
    const StageTimings& stages = densifier.matcher()->lastTimings();
    project.push_back(t.project);
    match.push_back(t.match);
    witness.push_back(t.witness);
    filters.push_back(t.filters);
    reproject.push_back(t.reproject);
    kernel.push_back(stages.total() - stages.transfers);
    confidence.push_back(stages.confidence);
  };
  WholeFrameMeasurement m;
  // Frames alone first: the process's peak memory then is the Densifier's (with the inputs and the
  // libraries), before OpenCV's SGBM adds its own buffers while the Densifier's are still held.
  // Three, since the second and third frame still add ~3 MiB (the witness then finds the
  // full-size buffers in place); later ones add nothing.
  constexpr int kFramesAlone = 3;
  for (int i = 0; i < kFramesAlone; ++i) densifier.run(frame.points);
  m.densifierPeakRssMiB = peakRssMiB();
  m.paired = pairWithOpenCvSgbm(sgbmPair, sgbm, threads, oneFrame, runs, warmups, idleMs);
  m.frameMs = m.paired.oursMs;
  m.projectMs = median(project);
  m.matchMs = median(match);
  m.witnessMs = median(witness);
  m.filtersMs = median(filters);
  m.reprojectMs = median(reproject);
  m.kernelMs = median(kernel);
  m.confidenceMs = median(confidence);
  m.cloudPoints = densifier.cloud().points.size();
  m.disparities = densifier.usedParameters().numDisparities;
  m.mode = densifier.lastMode();
  return m;
}

}  // namespace bench
}  // namespace lidar_sgm
