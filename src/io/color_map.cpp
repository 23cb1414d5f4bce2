#include "lidar_sgm/io/color_map.hpp"

#include <cstddef>
#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace lidar_sgm {
namespace io {

const std::array<cv::Vec3b, 256>& turboColors() {
  // Read off OpenCV's own map once, so that every picture uses the same colors.
  static const std::array<cv::Vec3b, 256> table = [] {
    cv::Mat ramp(1, 256, CV_8UC1);
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::Mat colored;
    cv::applyColorMap(ramp, colored, cv::COLORMAP_TURBO);
    std::array<cv::Vec3b, 256> colors{};
    for (int i = 0; i < 256; ++i) colors[static_cast<std::size_t>(i)] = colored.at<cv::Vec3b>(0, i);
    return colors;
  }();
  return table;
}

}  // namespace io
}  // namespace lidar_sgm
