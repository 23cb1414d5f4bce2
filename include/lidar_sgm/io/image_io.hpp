#pragma once
/// @file image_io.hpp  Reading and writing images and disparity files (libpng, libjpeg; images
/// held as cv::Mat, with the pixels and PNG bytes cv::imread / cv::imencode give).

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"

namespace lidar_sgm {
namespace io {

/// The largest image side the readers accept [px]: a PNG's size is checked from its
/// header before anything is decoded, other formats once decoded.
constexpr int kMaxImageSide = 16384;

/// Reads an image as stored (8 or 16 bit; 1, 3 or 4 channels, BGR order), decoded once; toGray()
/// and toColor() then give what matching and coloring need. PNG, JPEG and PGM/PPM only (checked
/// from the first bytes, not the name). Throws
/// std::runtime_error naming the file when it is missing, of another format, larger than
/// kMaxImageSide on a side (a PNG's size is checked from its header, before decoding), or of
/// another depth / channel count.
cv::Mat readImage(const std::string& path);
/// The size of the image at `path` (width x height), decoding nothing where the format allows:
/// a PNG's comes from its header (IHDR, bytes 16-23), so a PNG whose pixel data is damaged still
/// gives one (readImage() refuses it); JPEG and PGM/PPM are decoded as readImage() decodes them
/// (their headers are not parsed separately). Throws std::runtime_error "cannot read image '<path>':
/// <problem>" for what readImage() refuses before decoding (a missing file, another format, a
/// side above kMaxImageSide), a PNG cut short before its size, or one with no IHDR chunk first.
cv::Size imageSize(const std::string& path);
/// An 8- or 16-bit gray, BGR or BGRA image as gray of the same depth (BGR2GRAY, OpenCV's BT.601
/// weights; gray is returned as is, not copied). Throws std::invalid_argument for other depths or
/// channels.
cv::Mat toGray(const cv::Mat& image);
/// 8-bit BGR (16 bit scaled by 1/257, gray expanded, alpha dropped).
cv::Mat toColor(const cv::Mat& image);

/// Reads an image as gray, keeping 8 or 16 bits (color is converted, BGR order).
/// Throws std::runtime_error naming the file when it is missing or not an image.
cv::Mat readGrayImage(const std::string& path);

/// Reads a color image (8-bit BGR; gray is expanded) for coloring clouds and pictures.
cv::Mat readColorImage(const std::string& path);

/// A core view of an 8- or 16-bit single-channel cv::Mat (no copy).
GrayImageView grayView(const cv::Mat& gray);

/// KITTI disparity PNG (uint16, disparity*256, 0 = none) -> x16 disparities (kInvalidDisparity).
Image<std::int16_t> readKittiDisparity(const std::string& path);

/// KITTI disparity PNG -> float disparities [px], 0 where there is none (full 1/256 precision,
/// for ground truth).
Image<float> readKittiDisparityFloat(const std::string& path);

/// KITTI depth-completion PNG (uint16, metres*256, 0 = none) -> x16 disparities with d = F/z
/// (Eq. 3), F = focal length [px] * baseline [m].
Image<std::int16_t> readKittiDepthAsDisparity(const std::string& path, double focalBaseline);

/// x16 disparities -> KITTI disparity PNG (uint16, disparity*256). Invalid and non-positive
/// disparities are written as 0, which the format reserves for "no value".
cv::Mat toKittiDisparity(ImageView<const std::int16_t> disparity16);

/// Depth [m] (0 = none, as Densifier::depth()) -> KITTI depth-completion PNG (uint16,
/// round(metres*256), 0 = none). A depth the format cannot hold (>= 256 m, or one that rounds
/// to 0) is written as 0: "no value" is safer than a clamped, wrong one.
cv::Mat toKittiDepth(ImageView<const float> depth);

/// Confidence (0..255, core/confidence.hpp) -> 8-bit gray PNG of the same values: confidence / 255
/// is about the probability that the pixel's disparity is right; 0 = no disparity.
cv::Mat toConfidencePng(ImageView<const std::uint8_t> confidence);

/// Color picture of x16 disparities (turbo color map, 0 .. maxDisparity), invalid pixels black.
cv::Mat colorizeDisparity(ImageView<const std::int16_t> disparity16, double maxDisparity);

/// An 8-bit picture with each channel rounded to `levels` evenly spaced values (0 and 255
/// kept): fewer distinct colors make a PNG for the docs several times smaller. levels in
/// [2, 256] (256: an unchanged copy); throws std::invalid_argument otherwise or for a non-8-bit
/// image.
cv::Mat quantiseColors(const cv::Mat& image, int levels);

/// Writes through a temporary file in the same directory, renamed over `path` only once the
/// image is complete, so a crash never leaves a partial file. PNG only (`path` must end in .png):
/// an 8- or 16-bit image of 1, 3 (BGR) or 4 (BGRA) channels, the bytes cv::imencode(".png")
/// writes. Throws std::runtime_error (std::invalid_argument for bad parameters).
void writeImageAtomically(const std::string& path, const cv::Mat& image);
/// The same with OpenCV's imwrite parameter {cv::IMWRITE_PNG_COMPRESSION, 0-9}, e.g. 9 for the
/// smallest PNG (the default, level 1 with the SUB filter and RLE, favours speed, as OpenCV's).
void writeImageAtomically(const std::string& path, const cv::Mat& image, const std::vector<int>& params);

}  // namespace io
}  // namespace lidar_sgm
