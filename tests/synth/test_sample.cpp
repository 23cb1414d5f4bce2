// data/sample is what the generator makes: decode the committed files and compare them with a
// fresh render for the seed and options named in data/sample/README.md.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"
#include "common/test_paths.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

// Keep in step with data/sample/README.md:
//   lidar_sgm_synth -n 1 -seed 2024 -lidar_in_camera_view -out data/sample
constexpr std::uint32_t kSampleSeed = 2024;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

const synth::Frame& freshSample() {
  static const synth::Frame frame = [] {
    synth::FrameOptions options;
    options.seed = kSampleSeed;
    options.lidarInCameraViewOnly = true;
    return synth::renderFrame(options);
  }();
  return frame;
}

cv::Mat readPng(const std::string& folder) {
  const fs::path path = fs::path(test::kSampleDir) / folder / "000000.png";
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  EXPECT_FALSE(image.empty()) << path;
  return image;
}

long differingColorPixels(const cv::Mat& bgr, const Image<Rgb8>& rgb) {
  if (bgr.type() != CV_8UC3 || bgr.cols != rgb.width() || bgr.rows != rgb.height()) return -1;
  long differing = 0;
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      const Rgb8 q = rgb(x, y);
      differing += (p[0] != q.b || p[1] != q.g || p[2] != q.r) ? 1 : 0;
    }
  }
  return differing;
}

template <typename T>
long differingPixels(const cv::Mat& mat, const Image<T>& image) {
  if (mat.elemSize() != sizeof(T) || mat.channels() != 1 || mat.cols != image.width() || mat.rows != image.height()) {
    return -1;
  }
  long differing = 0;
  for (int y = 0; y < mat.rows; ++y) {
    for (int x = 0; x < mat.cols; ++x) differing += mat.at<T>(y, x) != image(x, y) ? 1 : 0;
  }
  return differing;
}

class SynthSample : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(fs::path(test::kSampleDir) / "calib" / "000000.txt")) {
      FAIL() << "data/sample is missing: regenerate it with the command in data/sample/README.md";
    }
  }
};

TEST_F(SynthSample, ImagesAndGroundTruthMatchAFreshRender) {
  const synth::Frame& frame = freshSample();
  EXPECT_EQ(differingColorPixels(readPng("image_2"), frame.left), 0);
  EXPECT_EQ(differingColorPixels(readPng("image_3"), frame.right), 0);
  EXPECT_EQ(differingPixels(readPng("disp_gt"), synth::encodeKittiDisparity(frame.disparity.view())), 0);
  EXPECT_EQ(differingPixels(readPng("depth_gt"), synth::encodeKittiDepth(frame.depth.view())), 0);
  EXPECT_EQ(differingPixels(readPng("mask"), frame.objectMask), 0);
  const Image<float> lidarDisparity = synth::projectLidarDisparity(frame.lidar, frame.rig);
  EXPECT_EQ(differingPixels(readPng("lidar_disp"), synth::encodeKittiDisparity(lidarDisparity.view())), 0);
}

TEST_F(SynthSample, LidarAndCalibrationMatchAFreshRender) {
  const synth::Frame& frame = freshSample();
  const fs::path dir(test::kSampleDir);
  EXPECT_EQ(readFile(dir / "calib" / "000000.txt"), synth::kittiCalibrationText(frame.rig, false));
  const std::string committed = readFile(dir / "velodyne" / "000000.bin");
  const std::string fresh = synth::velodyneBytes(frame.lidar);
  ASSERT_EQ(committed.size(), fresh.size());
  EXPECT_TRUE(committed == fresh) << "same point count, different bytes";
  EXPECT_LT(fs::file_size(dir / "velodyne" / "000000.bin"), 1u << 20);
}

TEST_F(SynthSample, StaysSmall) {
  std::uintmax_t bytes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(test::kSampleDir)) {
    if (entry.is_regular_file()) bytes += entry.file_size();
  }
  EXPECT_LT(bytes, 3u * 1024u * 1024u);
}

}  // namespace
}  // namespace lidar_sgm
