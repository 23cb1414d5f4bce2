#include "frame_pictures.hpp"

#include <cmath>

#include <opencv2/core.hpp>

#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "pictures.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

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
  std::vector<cv::Mat> rows{labelled(f.leftColor, f.dataset + " " + f.name + ": left image"),
                            labelled(groundTruthPicture(f), "ground truth (black: none)")};
  for (const auto& [method, disparity] : disparities) {
    rows.push_back(labelled(io::colorizeDisparity(disparity.view(), f.numDisparities), displayName(method)));
  }
  const Method stereoMethod{MethodKind::StereoSgm, 0.0};
  const Method fusedMethod{MethodKind::FusedSgm, kPaperAlpha};
  const Image<std::int16_t>* stereo = find(disparities, stereoMethod);
  const Image<std::int16_t>* fused = find(disparities, fusedMethod);
  for (const auto& [method, disparity] : {std::make_pair(stereoMethod, stereo), std::make_pair(fusedMethod, fused)}) {
    if (disparity == nullptr) continue;
    rows.push_back(labelled(errorMap(disparity->view(), f.groundTruth.view()),
                            "error, " + displayName(method) + " (blue < 0.19 px ... red > 48 px, black: no GT)"));
  }
  io::writeImageAtomically(dir + "/" + slug(f.dataset + "_" + f.name) + ".png", stack(rows));

  if (stereo != nullptr && fused != nullptr) {
    const std::string stereoName = displayName(stereoMethod);
    const std::string fusedName = displayName(fusedMethod);
    io::writeImageAtomically(
        dir + "/" + slug(f.dataset + "_" + f.name) + "_stereo_vs_fused.png",
        stack({labelled(io::colorizeDisparity(stereo->view(), f.numDisparities), stereoName),
               labelled(errorMap(stereo->view(), f.groundTruth.view()), stereoName + ": error"),
               labelled(io::colorizeDisparity(fused->view(), f.numDisparities), fusedName),
               labelled(errorMap(fused->view(), f.groundTruth.view()), fusedName + ": error")}));
  }
}

}  // namespace eval
}  // namespace lidar_sgm
