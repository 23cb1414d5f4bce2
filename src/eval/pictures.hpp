#pragma once
/// @file pictures.hpp  Pictures for the evaluation report: KITTI-style error maps, labelled
/// panels, vertical stacks.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace eval {

/// Disparity error per ground-truth pixel, |d_est - d_gt| [px], colored with the KITTI stereo
/// devkit's 10 log-scale bins (dark blue < 0.1875 px ... dark red >= 48 px; see pictures.cpp).
/// A missing estimate gets the last (largest-error) color; pixels without GT (<= 0 or NaN) are
/// black. Exact per pixel (no dilation). Returns 8-bit BGR. Throws std::invalid_argument when
/// the sizes differ.
cv::Mat errorMap(ImageView<const std::int16_t> estimate16, ImageView<const float> groundTruth);

/// The BGR color errorMap gives an error of `errorPx` (infinity: a missing estimate).
cv::Vec3b errorColor(double errorPx);

/// `image` (8-bit gray or BGR) with a dark bar on top holding `label` in white; the text is
/// scaled down when it would not fit the width. Returns 8-bit BGR.
cv::Mat labelled(const cv::Mat& image, const std::string& label);

/// The images one below the other (8-bit BGR); images of another width are resized to the
/// first's, keeping their aspect ratio. Empty input gives an empty Mat.
cv::Mat stack(const std::vector<cv::Mat>& images);

/// An 8-bit gray or BGR image as 8-bit BGR (no copy when it already is). Throws
/// std::invalid_argument for empty images and other types.
cv::Mat asBgr8(const cv::Mat& image);

}  // namespace eval
}  // namespace lidar_sgm
