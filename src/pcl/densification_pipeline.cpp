#include "lidar_sgm/pcl/densification_pipeline.hpp"

#include <chrono>
#include <stdexcept>
#include <string>

namespace lidar_sgm {

namespace {

template <typename T>
void copyInto(ImageView<const T> from, Image<T>& to) {
  to.resize(from.width, from.height);
  for (int y = 0; y < from.height; ++y) std::copy(from.row(y), from.row(y) + from.width, to.view().row(y));
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DensificationPipeline::DensificationPipeline() = default;

namespace {

template <typename T>
void checkPair(ImageView<const T> left, ImageView<const T> right) {
  if (left.empty() != right.empty()) {
    throw std::invalid_argument("setStereoPair: give both images or neither");
  }
  if (left.width != right.width || left.height != right.height) {
    throw std::invalid_argument("setStereoPair: the left image is " + sizeText(left.width, left.height) +
                                " but the right image is " + sizeText(right.width, right.height));
  }
}

}  // namespace

void DensificationPipeline::setStereoPair(ImageView<const std::uint8_t> left, ImageView<const std::uint8_t> right) {
  checkPair(left, right);
  left_ = Image<std::uint8_t>();
  right_ = Image<std::uint8_t>();
  left16_ = Image<std::uint16_t>();
  right16_ = Image<std::uint16_t>();
  if (left.empty()) return;
  copyInto(left, left_);
  copyInto(right, right_);
}

void DensificationPipeline::setStereoPair(ImageView<const std::uint16_t> left, ImageView<const std::uint16_t> right) {
  checkPair(left, right);
  left_ = Image<std::uint8_t>();
  right_ = Image<std::uint8_t>();
  left16_ = Image<std::uint16_t>();
  right16_ = Image<std::uint16_t>();
  if (left.empty()) return;
  copyInto(left, left16_);
  copyInto(right, right16_);
}

void DensificationPipeline::setColorImage(ImageView<const Rgb8> color) {
  if (color.empty()) {
    color_ = Image<Rgb8>();
    return;
  }
  copyInto(color, color_);
}

geometry::StereoCalibration DensificationPipeline::resolveCalibration() const {
  geometry::StereoCalibration c = calibration_;
  // The images fix the size when the calibration file had none; otherwise they must agree.
  const auto adopt = [&c](int width, int height, const char* what) {
    if (c.width == 0 && c.height == 0) {
      c.width = width;
      c.height = height;
    } else if (c.width != width || c.height != height) {
      throw std::invalid_argument(std::string("the ") + what + " is " + sizeText(width, height) +
                                  " but the calibration is for " + sizeText(c.width, c.height));
    }
  };
  if (!left_.empty()) adopt(left_.width(), left_.height(), "stereo pair");
  if (!left16_.empty()) adopt(left16_.width(), left16_.height(), "stereo pair");
  if (!color_.empty()) adopt(color_.width(), color_.height(), "color image");
  if (c.width == 0 && c.height == 0) {
    throw std::invalid_argument(
        "the calibration has no image size and there is no image to take it from: set a stereo pair, a color "
        "image, or a calibration with a size");
  }
  c.validate();
  return c;
}

geometry::DenseCloud DensificationPipeline::run(const std::vector<Eigen::Vector3f>& pointsLidar) {
  used_ = resolveCalibration();
  validate(params_);
  // The matcher keeps its buffers between frames; it is rebuilt only for another backend.
  if (!matcher_ || matcherBackend_ != backend_) {
    matcher_ = Matcher::create(backend_, params_);
    matcherBackend_ = backend_;
  } else {
    matcher_->setParameters(params_);
  }
  if (pointsLidar.empty()) throw std::invalid_argument("the input cloud is empty");

  auto start = std::chrono::steady_clock::now();
  projected_ = geometry::project(pointsLidar, used_, projectionOptions_);
  timings_.project = millisecondsSince(start);
  if (projected_.samples.empty()) {
    throw std::invalid_argument("no point of the cloud projects into the image (" + projected_.stats.describe() +
                                "): check the calibration");
  }

  start = std::chrono::steady_clock::now();
  const LidarPoints lidar = projected_.lidarPoints();
  disparity_.resize(used_.width, used_.height);
  GrayImageView left;
  GrayImageView right;
  if (!left_.empty()) {
    left = left_.view();
    right = right_.view();
  } else if (!left16_.empty()) {
    left = left16_.view();
    right = right16_.view();
  }
  matcher_->compute(left, right, &lidar, disparity_.view());
  lastMode_ = matcher_->lastMode();
  if (cropToScan_ && lastMode_ == MatchMode::LidarOnly) {
    // +-2 columns bridges the gaps between a beam's points (KITTI: ~1 px apart, with dropouts).
    geometry::cropToScanRows(disparity_.view(), projected_.samples, params_.lidarCoverageRows, 2);
  }
  timings_.match = millisecondsSince(start);

  start = std::chrono::steady_clock::now();
  geometry::DenseCloud cloud = geometry::reproject(disparity_.view(), used_, reprojectionOptions_);
  timings_.reproject = millisecondsSince(start);
  return cloud;
}

bool DensificationPipeline::colorAt(int x, int y, Rgb8& out) const {
  if (!color_.empty()) {
    out = color_(x, y);
    return true;
  }
  if (!left_.empty()) {
    const std::uint8_t g = left_(x, y);
    out = Rgb8{g, g, g};
    return true;
  }
  if (!left16_.empty()) {
    const auto g = static_cast<std::uint8_t>(left16_(x, y) >> 8);
    out = Rgb8{g, g, g};
    return true;
  }
  return false;
}

}  // namespace lidar_sgm
