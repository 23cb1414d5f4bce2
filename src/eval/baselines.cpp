#include "baselines.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace lidar_sgm {
namespace eval {
namespace {

// ---------------------------------------------------------------------------------------------
// OpenCV SGBM

/// SGBM takes CV_8U only; 16-bit images keep their 8 most significant bits (>> 8, not a rounding
/// conversion, so the result is exactly the high byte).
cv::Mat toEightBit(const cv::Mat& gray) {
  if (gray.type() == CV_8UC1) return gray;
  cv::Mat eight(gray.size(), CV_8UC1);
  for (int y = 0; y < gray.rows; ++y) {
    const std::uint16_t* in = gray.ptr<std::uint16_t>(y);
    std::uint8_t* out = eight.ptr<std::uint8_t>(y);
    for (int x = 0; x < gray.cols; ++x) out[x] = static_cast<std::uint8_t>(in[x] >> 8);
  }
  return eight;
}

void checkSgbmInput(const cv::Mat& left, const cv::Mat& right, int numDisparities, int blockSize) {
  if (left.empty() || right.empty()) throw std::invalid_argument("opencvSgbm: empty image");
  if (left.size() != right.size()) throw std::invalid_argument("opencvSgbm: left and right images differ in size");
  if (left.type() != right.type()) throw std::invalid_argument("opencvSgbm: left and right images differ in type");
  if (left.type() != CV_8UC1 && left.type() != CV_16UC1) {
    throw std::invalid_argument("opencvSgbm: images must be single-channel 8 or 16 bit");
  }
  if (numDisparities <= 0 || numDisparities % 16 != 0) {
    throw std::invalid_argument("opencvSgbm: numDisparities = " + std::to_string(numDisparities) +
                                ", must be a positive multiple of 16");
  }
  if (blockSize < 1 || blockSize % 2 == 0) {
    throw std::invalid_argument("opencvSgbm: blockSize = " + std::to_string(blockSize) + ", must be odd and >= 1");
  }
}

cv::Ptr<cv::StereoSGBM> makeSgbm(int numDisparities, int blockSize) {
  constexpr int kChannels = 1;  // gray input
  const int area = kChannels * blockSize * blockSize;
  // P1 = 8*cn*blockSize^2, P2 = 32*cn*blockSize^2: OpenCV's documented recommendation
  // (cv::StereoSGBM::create reference documentation).
  const int p1 = 8 * area;
  const int p2 = 32 * area;
  // disp12MaxDiff 1, uniquenessRatio 10, speckleWindowSize 100, speckleRange 32 are the values of
  // OpenCV's stereo_match sample (samples/cpp/stereo_match.cpp); preFilterCap 63 is that sample's
  // too (the largest cap SGBM accepts for its x-derivative prefilter).
  constexpr int kMinDisparity = 0;
  constexpr int kDisp12MaxDiff = 1;
  constexpr int kPreFilterCap = 63;
  constexpr int kUniquenessRatio = 10;
  constexpr int kSpeckleWindowSize = 100;
  constexpr int kSpeckleRange = 32;
  return cv::StereoSGBM::create(kMinDisparity, numDisparities, blockSize, p1, p2, kDisp12MaxDiff, kPreFilterCap,
                                kUniquenessRatio, kSpeckleWindowSize, kSpeckleRange, cv::StereoSGBM::MODE_SGBM_3WAY);
}

// ---------------------------------------------------------------------------------------------
// IP-Basic (Ku et al., CRV 2018), "fill_in_fast"

// The paper's constants: depths beyond 100 m are out of range (its max_depth), and a depth must
// exceed 0.1 m to count as a value (its validity threshold, used at every step).
constexpr float kMaxDepth = 100.0f;
constexpr float kMinValidDepth = 0.1f;

cv::Mat fullKernel(int size) { return cv::Mat::ones(size, size, CV_8U); }

/// The paper's 5x5 "diamond" kernel (its best-performing custom dilation kernel, Sec. III-B).
cv::Mat diamondKernel5() {
  return (cv::Mat_<std::uint8_t>(5, 5) << 0, 0, 1, 0, 0,  //
          0, 1, 1, 1, 0,                                  //
          1, 1, 1, 1, 1,                                  //
          0, 1, 1, 1, 0,                                  //
          0, 0, 1, 0, 0);
}

cv::Mat validMask(const cv::Mat& depth) { return depth > kMinValidDepth; }
cv::Mat emptyMask(const cv::Mat& depth) { return depth <= kMinValidDepth; }

/// Sparse x16 disparities -> inverted depth z' = 100 - z (0 = empty). Inverting makes near
/// points large, so the max-filters (dilations) below let near objects win over far ones at
/// edges, as the paper intends. Points at or beyond ~100 m invert to <= 0.1 and count as empty.
cv::Mat invertedDepthFromDisparity(const Image<std::int16_t>& disparity16, double focalBaseline) {
  cv::Mat inverted(disparity16.height(), disparity16.width(), CV_32F, cv::Scalar(0));
  for (int y = 0; y < disparity16.height(); ++y) {
    float* out = inverted.ptr<float>(y);
    for (int x = 0; x < disparity16.width(); ++x) {
      const std::int16_t d16 = disparity16(x, y);
      if (d16 == kInvalidDisparity || d16 <= 0) continue;  // no point (or no finite depth)
      const double depth = focalBaseline * kDisparityScale / d16;  // z = f*b / d (Eq. 3)
      if (depth <= kMinValidDepth) continue;
      const float value = kMaxDepth - static_cast<float>(depth);
      out[x] = value > kMinValidDepth ? value : 0.0f;
    }
  }
  return inverted;
}

/// Steps "small hole fill" and "large hole fill": empty pixels take the value of a full-kernel
/// dilation (the largest = nearest neighbouring depth); valid pixels are kept.
void fillEmptyFromDilation(cv::Mat& depth, int kernelSize) {
  cv::Mat dilated;
  cv::dilate(depth, dilated, fullKernel(kernelSize));
  dilated.copyTo(depth, emptyMask(depth));
}

/// Step "extension to top of frame": the LiDAR sees nothing above its top beam, so each column's
/// topmost value is repeated up to row 0 (the paper's remedy for sky / tall objects).
void extendColumnsToTop(cv::Mat& depth) {
  for (int x = 0; x < depth.cols; ++x) {
    int top = 0;
    while (top < depth.rows && depth.at<float>(top, x) <= kMinValidDepth) ++top;
    if (top == depth.rows) continue;  // empty column: nothing to extend
    const float value = depth.at<float>(top, x);
    for (int y = 0; y < top; ++y) depth.at<float>(y, x) = value;
  }
}

/// Step "Gaussian blur", applied only where there is a value (the fast pipeline's choice), so
/// empty pixels stay empty and the valid mask is unchanged.
void gaussianBlurValid(cv::Mat& depth) {
  const cv::Mat valid = validMask(depth);
  cv::Mat blurred;
  cv::GaussianBlur(depth, blurred, cv::Size(5, 5), 0);
  blurred.copyTo(depth, valid);
}

/// Inverted depth -> x16 disparities: z = 100 - z', d = f*b / z. Empty pixels, depths <= 0.1 m
/// and disparities int16 x16 cannot hold (> 2047 px) are invalid.
Image<std::int16_t> disparityFromInvertedDepth(const cv::Mat& inverted, double focalBaseline) {
  Image<std::int16_t> disparity16(inverted.cols, inverted.rows, kInvalidDisparity);
  for (int y = 0; y < inverted.rows; ++y) {
    const float* in = inverted.ptr<float>(y);
    for (int x = 0; x < inverted.cols; ++x) {
      if (in[x] <= kMinValidDepth) continue;  // not filled
      const double depth = static_cast<double>(kMaxDepth) - in[x];
      if (depth <= kMinValidDepth) continue;
      const double d16 = std::round(focalBaseline * kDisparityScale / depth);
      if (d16 > std::numeric_limits<std::int16_t>::max()) continue;
      disparity16(x, y) = static_cast<std::int16_t>(d16);
    }
  }
  return disparity16;
}

}  // namespace

Image<std::int16_t> opencvSgbm(const cv::Mat& leftGray, const cv::Mat& rightGray, int numDisparities, int blockSize) {
  checkSgbmInput(leftGray, rightGray, numDisparities, blockSize);
  cv::Mat disparity;  // CV_16S, x16, (minDisparity - 1) * 16 where SGBM has no value
  makeSgbm(numDisparities, blockSize)->compute(toEightBit(leftGray), toEightBit(rightGray), disparity);
  Image<std::int16_t> result(disparity.cols, disparity.rows, kInvalidDisparity);
  for (int y = 0; y < disparity.rows; ++y) {
    const std::int16_t* row = disparity.ptr<std::int16_t>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      // minDisparity is 0, so every value below 0 is SGBM's "invalid" marker.
      if (row[x] >= 0) result(x, y) = row[x];
    }
  }
  return result;
}

Image<std::int16_t> morphologicalCompletion(const Image<std::int16_t>& sparseDisparity16, double focalBaseline) {
  if (!(focalBaseline > 0.0) || !std::isfinite(focalBaseline)) {
    throw std::invalid_argument("morphologicalCompletion: focalBaseline = " + std::to_string(focalBaseline) +
                                ", must be finite and > 0");
  }
  if (sparseDisparity16.empty()) return {};
  // 1. Depth inversion (z' = 100 - z on valid pixels).
  cv::Mat depth = invertedDepthFromDisparity(sparseDisparity16, focalBaseline);
  // 2. Custom-kernel dilation: 5x5 diamond, grows each point into a small patch.
  cv::dilate(depth, depth, diamondKernel5());
  // 3. Small hole closure: 5x5 full-kernel closing joins neighbouring patches.
  cv::morphologyEx(depth, depth, cv::MORPH_CLOSE, fullKernel(5));
  // 4. Small hole fill: empty pixels from a 7x7 full-kernel dilation.
  fillEmptyFromDilation(depth, 7);
  // 5. Extension to the top of the frame.
  extendColumnsToTop(depth);
  // 6. Large hole fill: remaining empty pixels from a 31x31 full-kernel dilation.
  fillEmptyFromDilation(depth, 31);
  // 7. 5x5 median blur removes the outliers the dilations spread.
  cv::Mat median;
  cv::medianBlur(depth, median, 5);
  // 8. 5x5 Gaussian blur on valid pixels smooths the piecewise-constant surfaces.
  gaussianBlurValid(median);
  // 9. Inversion back to depth, and depth -> disparity.
  return disparityFromInvertedDepth(median, focalBaseline);
}

}  // namespace eval
}  // namespace lidar_sgm
