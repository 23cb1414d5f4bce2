#include "bench_frame_io.hpp"

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lidar_sgm/eval/simulated_lidar.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace bench {
namespace {

const char* kKitti2015Folder = "kitti_stereo2015_training_sample";

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// Copies an 8-bit gray cv::Mat into a core image. The bench times 8-bit pairs only: OpenCV's
/// StereoSGBM, its peer in the same run, takes no 16-bit images.
Image<std::uint8_t> toImage(const cv::Mat& gray, const std::string& path) {
  if (gray.type() != CV_8UC1) {
    throw std::runtime_error(path + ": the bench times 8-bit images (OpenCV's SGBM takes no 16-bit ones)");
  }
  Image<std::uint8_t> out(gray.cols, gray.rows);
  for (int y = 0; y < gray.rows; ++y) {
    std::memcpy(out.view().row(y), gray.ptr<std::uint8_t>(y), static_cast<std::size_t>(gray.cols));
  }
  return out;
}

/// A cv::Mat header over a core image (no copy), for OpenCV functions that only read it.
cv::Mat matView(const Image<std::uint8_t>& image) {
  return cv::Mat(image.height(), image.width(), CV_8UC1, const_cast<std::uint8_t*>(image.data()));
}

void readPair(Frame& frame, const std::string& leftPath, const std::string& rightPath) {
  frame.left = toImage(io::readGrayImage(leftPath), leftPath);
  frame.right = toImage(io::readGrayImage(rightPath), rightPath);
  if (frame.left.width() != frame.right.width() || frame.left.height() != frame.right.height()) {
    throw std::runtime_error("left and right images differ in size: " +
                             sizeText(frame.left.width(), frame.left.height()) + " (" + leftPath + "), " +
                             sizeText(frame.right.width(), frame.right.height()) + " (" + rightPath + ")");
  }
}

}  // namespace

Frame loadKittiP1Frame(const std::string& dataRoot, const std::string& id) {
  const std::filesystem::path folder = std::filesystem::path(dataRoot) / kKitti2015Folder;
  if (!std::filesystem::is_directory(folder)) {
    throw std::runtime_error("no " + std::string(kKitti2015Folder) + " under " + dataRoot +
                             ": give -data ROOT, -left L -right R -lidar D, or -synthetic");
  }
  const std::string left = (folder / "image_2" / (id + ".png")).string();
  const std::string right = (folder / "image_3" / (id + ".png")).string();
  const std::string groundTruth = (folder / "disp_occ_0" / (id + ".png")).string();
  Frame frame;
  readPair(frame, left, right);
  const Image<float> gt = io::readKittiDisparityFloat(groundTruth);
  // Default options, as protocol P1: HDL-64E-like rows for KITTI's intrinsics, every 2nd pixel,
  // 0.1 px noise, seed 1. The mask of input pixels only matters for scoring.
  Image<std::uint8_t> inputMask;
  frame.lidar = eval::simulateLidarFromGroundTruth(gt.view(), {}, inputMask);
  frame.source = "KITTI 2015 training " + id + ", LiDAR: 64 beams sampled from its GT (protocol P1)";
  frame.files = {{"left", left}, {"right", right}, {"GT", groundTruth}};
  return frame;
}

Frame loadFileFrame(const std::string& leftPath, const std::string& rightPath, const std::string& lidarPath) {
  Frame frame;
  readPair(frame, leftPath, rightPath);
  const Image<std::int16_t> sparse = io::readKittiDisparity(lidarPath);  // x16, kInvalidDisparity = none
  if (sparse.width() != frame.width() || sparse.height() != frame.height()) {
    throw std::runtime_error(lidarPath + " is " + sizeText(sparse.width(), sparse.height()) + " but the images are " +
                             sizeText(frame.width(), frame.height()));
  }
  frame.lidar = LidarPoints::fromDisparityImage(sparse.view());
  frame.source = "files, LiDAR from a sparse KITTI disparity PNG";
  frame.files = {{"left", leftPath}, {"right", rightPath}, {"LiDAR", lidarPath}};
  return frame;
}

Frame resizedFrame(const Frame& frame, int width, int height) {
  const bool shrink = static_cast<long>(width) * height < static_cast<long>(frame.width()) * frame.height();
  const int interpolation = shrink ? cv::INTER_AREA : cv::INTER_LINEAR;
  Frame out;
  cv::Mat resized;
  cv::resize(matView(frame.left), resized, cv::Size(width, height), 0, 0, interpolation);
  out.left = toImage(resized, "resized left image");
  cv::resize(matView(frame.right), resized, cv::Size(width, height), 0, 0, interpolation);
  out.right = toImage(resized, "resized right image");
  out.lidar = scaledLidar(frame.lidar, width, height);
  out.source = frame.source + " (resized to " + sizeText(width, height) + ")";
  out.files = frame.files;
  return out;
}

}  // namespace bench
}  // namespace lidar_sgm
