#include "frame_pictures.hpp"

#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "pictures.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

/// The pictures go into the docs, so they are kept small (a nine-panel KITTI-sized picture
/// under 500 KB): every panel at half the frame's size, 32 levels per channel, PNG level 9.
/// Disparity and error maps are subsampled (nearest pixel: no blended colors, which PNG would
/// store as noise); the photo is area-averaged.
constexpr double kPanelScale = 0.5;
constexpr int kColorLevels = 32;
constexpr int kPngCompression = 9;

struct Panel {
  cv::Mat image;
  std::string label;
  bool photo = false;
};

cv::Mat half(const Panel& panel) {
  cv::Mat small;
  cv::resize(panel.image, small, cv::Size(), kPanelScale, kPanelScale, panel.photo ? cv::INTER_AREA : cv::INTER_NEAREST);
  return small;
}

/// Labelled, half-size panels, one below the other.
void writePanels(const std::string& path, const std::vector<Panel>& panels) {
  std::vector<cv::Mat> rows;
  for (const Panel& panel : panels) rows.push_back(labelled(half(panel), panel.label));
  io::writeImageAtomically(path, io::quantiseColors(stack(rows), kColorLevels),
                           {cv::IMWRITE_PNG_COMPRESSION, kPngCompression});
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

const Image<std::int16_t>* find(const std::vector<std::pair<Method, Image<std::int16_t>>>& disparities,
                                const Method& method) {
  for (const auto& [m, disparity] : disparities) {
    if (sameMethod(m, method)) return &disparity;
  }
  return nullptr;
}

}  // namespace

void writeFramePictures(const std::string& dir, const EvalFrame& f,
                        const std::vector<std::pair<Method, Image<std::int16_t>>>& disparities) {
  std::vector<Panel> panels{{f.leftColor, f.dataset + " " + f.name + ": left image", true},
                            {groundTruthPicture(f), "ground truth (black: none)"}};
  for (const auto& [method, disparity] : disparities) {
    panels.push_back({io::colorizeDisparity(disparity.view(), f.numDisparities), displayName(method)});
  }
  const Method stereoMethod{MethodKind::StereoSgm, 0.0};
  const Method fusedMethod{MethodKind::FusedSgm, kPaperAlpha};
  const Image<std::int16_t>* stereo = find(disparities, stereoMethod);
  const Image<std::int16_t>* fused = find(disparities, fusedMethod);
  for (const auto& [method, disparity] : {std::make_pair(stereoMethod, stereo), std::make_pair(fusedMethod, fused)}) {
    if (disparity == nullptr) continue;
    panels.push_back({errorMap(disparity->view(), f.groundTruth.view()),
                      "error, " + displayName(method) + " (blue < 0.19 px ... red > 48 px, black: no GT)"});
  }
  writePanels(dir + "/" + slug(f.dataset + "_" + f.name) + ".png", panels);

  if (stereo != nullptr && fused != nullptr) {
    const std::string stereoName = displayName(stereoMethod);
    const std::string fusedName = displayName(fusedMethod);
    writePanels(dir + "/" + slug(f.dataset + "_" + f.name) + "_stereo_vs_fused.png",
                {{io::colorizeDisparity(stereo->view(), f.numDisparities), stereoName},
                 {errorMap(stereo->view(), f.groundTruth.view()), stereoName + ": error"},
                 {io::colorizeDisparity(fused->view(), f.numDisparities), fusedName},
                 {errorMap(fused->view(), f.groundTruth.view()), fusedName + ": error"}});
  }
}

}  // namespace eval
}  // namespace lidar_sgm
