#include "lidar_sgm/io/opencv.hpp"

namespace lidar_sgm {
namespace io {

cv::Mat toOpenCvDisparity(ImageView<const std::int16_t> disparity16, int minDisparity) {
  const auto invalid = static_cast<std::int16_t>(openCvInvalidDisparity16(minDisparity));
  cv::Mat out(disparity16.height, disparity16.width, CV_16SC1);
  for (int y = 0; y < disparity16.height; ++y) {
    const std::int16_t* in = disparity16.row(y);
    auto* row = out.ptr<std::int16_t>(y);
    for (int x = 0; x < disparity16.width; ++x) row[x] = in[x] == kInvalidDisparity ? invalid : in[x];
  }
  return out;
}

}  // namespace io
}  // namespace lidar_sgm
