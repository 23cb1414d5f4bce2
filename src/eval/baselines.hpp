#pragma once
/// @file baselines.hpp  The methods LiDAR-SGM is compared with in the evaluation protocols:
/// OpenCV's stereo SGBM (images only) and IP-Basic's morphological completion (LiDAR only).

#include <cstdint>

#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace eval {

/// cv::StereoSGBM (MODE_SGBM_3WAY, minDisparity 0) with OpenCV's recommended penalties and the
/// stereo_match sample's post-filters; see baselines.cpp for every value and its source.
/// `leftGray`, `rightGray`: rectified, single channel, 8 or 16 bit (16 bit is reduced to 8 by
/// >> 8, as SGBM takes CV_8U only), same size and depth. `numDisparities`: positive multiple of
/// 16; `blockSize`: odd, >= 1. Returns x16 disparities, kInvalidDisparity where SGBM has none.
/// Throws std::invalid_argument on empty or mismatched images or bad parameters.
Image<std::int16_t> opencvSgbm(const cv::Mat& leftGray, const cv::Mat& rightGray, int numDisparities = 128,
                               int blockSize = 5);

/// LiDAR-only depth completion of Ku, Harakeh, Waslander, "In Defense of Classical Image
/// Processing: Fast Depth Completion on the CPU" (CRV 2018, "IP-Basic"), its default
/// "fill_in_fast" pipeline, run on depth z = focalBaseline / d.
/// `sparseDisparity16`: x16 disparities, kInvalidDisparity (or <= 0) where there is no point.
/// `focalBaseline`: f [px] * b [m], > 0. Returns x16 disparities, kInvalidDisparity where the
/// pipeline leaves no depth (> 0.1 m). Throws std::invalid_argument for focalBaseline <= 0.
Image<std::int16_t> morphologicalCompletion(const Image<std::int16_t>& sparseDisparity16, double focalBaseline);

}  // namespace eval
}  // namespace lidar_sgm
