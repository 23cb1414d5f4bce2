#include "frame_images.hpp"

#include <stdexcept>

#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace python {

FrameImages frameImages(const pybind11::object& left, const pybind11::object& right) {
  if (!right.is_none() && left.is_none()) throw std::invalid_argument("right needs left");
  FrameImages images;
  if (!left.is_none()) images.left = imageFromArray(left, "left");
  if (!right.is_none()) images.right = imageFromArray(right, "right");
  return images;
}

void setImages(Densifier& densifier, const FrameImages& images, bool color) {
  if (!images.right.mat.empty()) {
    const cv::Mat leftGray = grayOf(images.left.mat);
    const cv::Mat rightGray = grayOf(images.right.mat);
    if (leftGray.depth() != rightGray.depth()) {
      throw std::invalid_argument("the left and right images differ in bit depth (8 vs 16 bit)");
    }
    densifier.setStereoPair(io::grayView(leftGray), io::grayView(rightGray));  // copied by the Densifier
  } else {
    densifier.clearStereoPair();
  }
  if (color && !images.left.mat.empty()) {
    const cv::Mat rgb = colorOf(images.left.mat);
    densifier.setColorImage(rgbView(rgb));  // copied by the Densifier
  } else {
    densifier.setColorImage(ImageView<const Rgb8>());
  }
}

}  // namespace python
}  // namespace lidar_sgm
