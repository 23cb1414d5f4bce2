#include "lidar_sgm/io/pcl_image.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace lidar_sgm {
namespace io {

pcl::PointCloud<pcl::RGB> toPclImage(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("toPclImage: the image is empty");
  if (image.depth() != CV_8U) {
    throw std::invalid_argument("toPclImage: expected an 8-bit image, got depth " + std::to_string(image.depth()));
  }
  cv::Mat bgr;
  if (image.channels() == 1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else if (image.channels() == 3) {
    bgr = image;
  } else {
    throw std::invalid_argument("toPclImage: expected 1, 3 or 4 channels, got " + std::to_string(image.channels()));
  }
  pcl::PointCloud<pcl::RGB> cloud(static_cast<std::uint32_t>(bgr.cols), static_cast<std::uint32_t>(bgr.rows));
  for (int y = 0; y < bgr.rows; ++y) {
    const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      pcl::RGB& p = cloud.at(x, y);
      p.b = row[x][0];
      p.g = row[x][1];
      p.r = row[x][2];
      p.a = 255;
    }
  }
  return cloud;
}

}  // namespace io
}  // namespace lidar_sgm
