#pragma once
// The per-frame pictures of an evaluation run: every method's disparity beside the GT, and the
// stereo-only against fused comparison the README shows.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/eval/eval_frame.hpp"
#include "lidar_sgm/eval/methods.hpp"

namespace lidar_sgm {
namespace eval {

/// Writes DIR/<slug(dataset_name)>.png (left image, GT, each method's disparity, the error of
/// stereo-only and of LiDAR-SGM at the paper's alpha) and, when both are present,
/// DIR/<slug>_stereo_vs_fused.png (without the input image: third-party frames stay out of the
/// repository, only our results go in). Panels at half the frame's size, 32 levels per channel,
/// PNG level 9: small enough for the docs.
void writeFramePictures(const std::string& dir, const EvalFrame& frame,
                        const std::vector<std::pair<Method, Image<std::int16_t>>>& disparities);

}  // namespace eval
}  // namespace lidar_sgm
