#include "core/frame_checks.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace {

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The right image must match the left one in size and bit depth.
void checkSamePair(const GrayImageView& left, const GrayImageView& right) {
  if (right.width() != left.width() || right.height() != left.height()) {
    throw std::invalid_argument("left and right images differ in size: left " + sizeText(left.width(), left.height()) +
                                ", right " + sizeText(right.width(), right.height()));
  }
  if (left.gray8.empty() != right.gray8.empty()) {
    throw std::invalid_argument("left and right images differ in bit depth (one is 8-bit, the other 16-bit)");
  }
}

void checkOutput(ImageView<std::int16_t> disparity, int width, int height) {
  if (disparity.data == nullptr || disparity.width != width || disparity.height != height ||
      disparity.stride < width) {
    throw std::invalid_argument("the output disparity image is " + sizeText(disparity.width, disparity.height) +
                                " but the frame is " + sizeText(width, height));
  }
}

[[noreturn]] void throwNoInput() {
  throw std::invalid_argument(
      "no input to match: give a right image (stereo), LiDAR points (LiDAR-only), or both (fused)");
}

void checkVerticalView(const VerticalView& vertical, bool haveRight) {
  const bool haveUp = !vertical.up.empty();
  if (!haveUp && vertical.baselineRatio != 0.0) {
    std::ostringstream os;
    os << "VerticalView has baselineRatio " << vertical.baselineRatio
       << " but no up image: pass the up image, or an empty VerticalView (ratio 0) for two cameras";
    throw std::invalid_argument(os.str());
  }
  if (haveUp && !haveRight) {
    throw std::invalid_argument(
        "an up image (third camera) needs a right image too: Triple-SGM adds the vertical pair to the "
        "horizontal one; there is no up-only mode");
  }
  if (haveUp && (!std::isfinite(vertical.baselineRatio) || vertical.baselineRatio <= 0.0 ||
                 vertical.baselineRatio > 4.0)) {
    std::ostringstream os;
    os << "invalid VerticalView baselineRatio = " << vertical.baselineRatio
       << ": must be b_up / b, finite, in (0, 4]";
    throw std::invalid_argument(os.str());
  }
}

// The cameras of a stereo-only or fused frame, and the LiDAR's size against theirs.
void checkCameras(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                  const LidarPoints* lidar) {
  if (left.empty()) throw std::invalid_argument("the left image is empty");
  const int width = left.width();
  const int height = left.height();
  checkSamePair(left, right);
  if (lidar != nullptr && !lidar->empty() && (lidar->width() != width || lidar->height() != height)) {
    throw std::invalid_argument("LiDAR points are for a " + sizeText(lidar->width(), lidar->height()) +
                                " image but the stereo images are " + sizeText(width, height));
  }
  const GrayImageView& up = vertical.up;
  if (up.empty()) return;
  if (up.width() != width || up.height() != height) {
    throw std::invalid_argument("left and up images differ in size: left " + sizeText(width, height) + ", up " +
                                sizeText(up.width(), up.height()));
  }
  if (left.gray8.empty() != up.gray8.empty()) {
    throw std::invalid_argument("left and up images differ in bit depth (one is 8-bit, the other 16-bit)");
  }
}

}  // namespace

CheckedFrame checkFrame(const GrayImageView& left, const GrayImageView& right, const VerticalView& vertical,
                        const LidarPoints* lidar, ImageView<std::int16_t> disparity) {
  const bool haveLidar = lidar != nullptr && !lidar->empty();
  const bool haveRight = !right.empty();
  checkVerticalView(vertical, haveRight);
  CheckedFrame frame;
  if (haveRight) {
    frame.mode = haveLidar ? MatchMode::Fused : MatchMode::StereoOnly;
    checkCameras(left, right, vertical, lidar);
    frame.width = left.width();
    frame.height = left.height();
  } else if (haveLidar) {
    frame.mode = MatchMode::LidarOnly;
    frame.width = lidar->width();
    frame.height = lidar->height();
    if (!left.empty() && (left.width() != frame.width || left.height() != frame.height)) {
      throw std::invalid_argument("LiDAR points are for a " + sizeText(frame.width, frame.height) +
                                  " image but the left image is " + sizeText(left.width(), left.height()));
    }
  } else {
    throwNoInput();
  }
  checkOutput(disparity, frame.width, frame.height);
  return frame;
}

CheckedFrame checkDeviceFrame(const DeviceFrame& frame, ImageView<std::int16_t> disparity) {
  const bool haveLidar = frame.lidar != nullptr && frame.lidarCount > 0;
  const bool haveRight = !frame.right.empty();
  if (!haveRight && !haveLidar) throwNoInput();
  CheckedFrame checked;
  checked.mode = haveRight ? (haveLidar ? MatchMode::Fused : MatchMode::StereoOnly) : MatchMode::LidarOnly;
  checked.width = frame.left.empty() ? frame.width : frame.left.width();
  checked.height = frame.left.empty() ? frame.height : frame.left.height();
  if (haveRight && frame.left.empty()) throw std::invalid_argument("the left image is empty");
  if (checked.width <= 0 || checked.height <= 0) {
    throw std::invalid_argument("DeviceFrame without a left image must give its size (width, height), got " +
                                sizeText(checked.width, checked.height));
  }
  if (haveRight) checkSamePair(frame.left, frame.right);
  checkOutput(disparity, checked.width, checked.height);
  return checked;
}

}  // namespace lidar_sgm
