#pragma once
/// @file opencv.hpp  Our in-memory disparities in OpenCV's own convention, for code that
/// mixes lidar_sgm with cv::StereoSGBM results or OpenCV's disparity tools.

#include <cstdint>

#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace io {

/// x16 disparities (kInvalidDisparity = -32768 where none) as cv::StereoSGBM returns them:
/// CV_16S, the same x16 values, and its invalid value (minDisparity - 1) * 16
/// (openCvInvalidDisparity16) where there is none. `minDisparity` is the one the disparity
/// was matched with (Parameters::minDisparity). A copy; the input is not changed.
cv::Mat toOpenCvDisparity(ImageView<const std::int16_t> disparity16, int minDisparity);

}  // namespace io
}  // namespace lidar_sgm
