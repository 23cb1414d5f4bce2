#pragma once
/// @file sgm_densification_opencv.hpp  cv::Mat images for SGMDensification.
///
/// Header-only on purpose: lidar_sgm_pcl (the class) stays free of OpenCV, and only code that
/// includes this header needs it. Link lidar_sgm::io there, whose helpers (io::grayView,
/// io::toGray, io::toPclImage) do every conversion. Free functions rather than members,
/// because a member taking cv::Mat would put OpenCV into the class's own header; they are
/// found by argument-dependent lookup: setStereoPair(sgm, left, right).

#include <opencv2/core.hpp>

#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/pcl_image.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {

/// The rectified pair as cv::Mat:
/// - both 8-bit BGR or BGRA: matched in gray (BGR2GRAY weights), the left one colors the
///   output unless setColorImage() was called (as the pcl::RGB overload);
/// - otherwise 8- or 16-bit gray, BGR or BGRA, both of the same depth: converted to gray of
///   that depth (BGR2GRAY) and matched at it; the output is colored in gray unless
///   setColorImage() was called.
/// Throws std::invalid_argument (from io) for another depth or channel count: a wrong type is a
/// programming error found at the call. Sizes are checked in filter(), as for every setter.
template <typename PointInT, typename PointOutT>
void setStereoPair(SGMDensification<PointInT, PointOutT>& sgm, const cv::Mat& left, const cv::Mat& right) {
  const auto isColor8 = [](const cv::Mat& m) { return m.depth() == CV_8U && (m.channels() == 3 || m.channels() == 4); };
  if (isColor8(left) && isColor8(right)) {
    sgm.setStereoPair(io::toPclImage(left), io::toPclImage(right));
    return;
  }
  // The gray images must outlive grayView(); setStereoPair copies them.
  const cv::Mat grayLeft = io::toGray(left);
  const cv::Mat grayRight = io::toGray(right);
  sgm.setStereoPair(io::grayView(grayLeft), io::grayView(grayRight));
}

/// The image that colors the output: 8-bit BGR, BGRA or gray, the left camera's size.
/// Throws std::invalid_argument (from io) for another type.
template <typename PointInT, typename PointOutT>
void setColorImage(SGMDensification<PointInT, PointOutT>& sgm, const cv::Mat& bgr) {
  sgm.setColorImage(io::toPclImage(bgr));
}

}  // namespace lidar_sgm
