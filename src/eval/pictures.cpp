#include "pictures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace lidar_sgm {
namespace eval {
namespace {

/// The KITTI stereo devkit's log-color table (devkit_stereo_flow/cpp: the `LC` table that
/// `DisparityImage::errorImage` uses with log_colors): its bins are on the error normalized by 3 px (0, 0.0625, 0.125, ... 16),
/// here multiplied back to pixels: [0, 0.1875), [0.1875, 0.375), ... [48, inf). The devkit's
/// normalization also takes the 5 % relative term, min(e / 3, 20 e / |d_gt|); this map shows
/// the absolute error only, so a color means the same number of pixels everywhere.
struct ErrorBin {
  double upperPx;  ///< exclusive upper bound of the bin [px]
  cv::Vec3b bgr;   ///< the devkit's RGB, in OpenCV's BGR order
};
const std::array<ErrorBin, 10> kErrorBins = {{
    {0.1875, {149, 54, 49}},
    {0.375, {180, 117, 69}},
    {0.75, {209, 173, 116}},
    {1.5, {233, 217, 171}},
    {3.0, {248, 243, 224}},
    {6.0, {144, 224, 254}},
    {12.0, {97, 174, 253}},
    {24.0, {67, 109, 244}},
    {48.0, {39, 48, 215}},
    {std::numeric_limits<double>::infinity(), {38, 0, 165}},
}};

const cv::Scalar kBarColor(40, 40, 40);
const cv::Scalar kTextColor(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kLabelScale = 0.6;

}  // namespace

cv::Vec3b errorColor(double errorPx) {
  for (const ErrorBin& bin : kErrorBins) {
    if (errorPx < bin.upperPx) return bin.bgr;
  }
  return kErrorBins.back().bgr;  // infinity and NaN: the largest error
}

cv::Mat errorMap(ImageView<const std::int16_t> estimate16, ImageView<const float> groundTruth) {
  if (estimate16.width != groundTruth.width || estimate16.height != groundTruth.height) {
    throw std::invalid_argument("errorMap: estimate and ground truth differ in size");
  }
  cv::Mat map(groundTruth.height, groundTruth.width, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < groundTruth.height; ++y) {
    cv::Vec3b* out = map.ptr<cv::Vec3b>(y);
    for (int x = 0; x < groundTruth.width; ++x) {
      const float gt = groundTruth(x, y);
      if (!(gt > 0.0f)) continue;  // no GT (0 or NaN), as in eval::evaluateDisparity: black
      const std::int16_t e = estimate16(x, y);
      const double error = e == kInvalidDisparity
                               ? std::numeric_limits<double>::infinity()
                               : std::abs(static_cast<double>(e) / kDisparityScale - static_cast<double>(gt));
      out[x] = errorColor(error);
    }
  }
  return map;
}

cv::Mat asBgr8(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("asBgr8: empty image");
  if (image.type() == CV_8UC3) return image;
  if (image.type() != CV_8UC1) throw std::invalid_argument("asBgr8: image must be 8-bit gray or BGR");
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

cv::Mat labelled(const cv::Mat& image, const std::string& label) {
  const cv::Mat bgr = asBgr8(image);
  int baseline = 0;
  double scale = kLabelScale;
  cv::Size size = cv::getTextSize(label, kFont, scale, 1, &baseline);
  const int maxTextWidth = std::max(1, bgr.cols - 12);
  if (size.width > maxTextWidth) {  // shrink long labels to the width rather than cut them off
    scale *= static_cast<double>(maxTextWidth) / size.width;
    size = cv::getTextSize(label, kFont, scale, 1, &baseline);
  }
  const int barHeight = cvRound(cv::getTextSize("Ag", kFont, kLabelScale, 1, &baseline).height * 2.2);
  cv::Mat result(bgr.rows + barHeight, bgr.cols, CV_8UC3, kBarColor);
  bgr.copyTo(result(cv::Rect(0, barHeight, bgr.cols, bgr.rows)));
  cv::putText(result, label, {6, (barHeight + size.height) / 2}, kFont, scale, kTextColor, 1, cv::LINE_AA);
  return result;
}

cv::Mat stack(const std::vector<cv::Mat>& images) {
  if (images.empty()) return {};
  const int width = asBgr8(images.front()).cols;
  std::vector<cv::Mat> rows;
  for (const cv::Mat& image : images) {
    cv::Mat bgr = asBgr8(image);
    if (bgr.cols != width) {
      const int height = std::max(1, cvRound(static_cast<double>(bgr.rows) * width / bgr.cols));
      cv::Mat resized;
      // Area averaging when shrinking (no aliasing), bilinear when enlarging.
      cv::resize(bgr, resized, cv::Size(width, height), 0, 0, bgr.cols > width ? cv::INTER_AREA : cv::INTER_LINEAR);
      bgr = resized;
    }
    rows.push_back(bgr);
  }
  cv::Mat result;
  cv::vconcat(rows, result);
  return result;
}

}  // namespace eval
}  // namespace lidar_sgm
