// Protocol P1: GT frames with a simulated 64-beam LiDAR; and the helpers every loader shares.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/eval/simulated_lidar.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace eval {

namespace fs = std::filesystem;

std::string resolveDataRoot(const std::string& option) {
  if (!option.empty()) return option;
  const char* env = std::getenv("LIDAR_SGM_DATA");
  if (env != nullptr && *env != '\0') return env;
  return "../shared/data";
}

int numDisparitiesFor(double maxDisparity) {
  const double needed = maxDisparity + 8.0;
  if (!(needed > 128.0)) return 128;
  return 16 * static_cast<int>(std::ceil(needed / 16.0));
}

void setLidarInput(EvalFrame& frame, const LidarPoints& input) {
  const int w = input.width();
  const int h = input.height();
  frame.lidar = input;
  frame.lidarSparse = Image<std::int16_t>(w, h, kInvalidDisparity);
  frame.exclude = Image<std::uint8_t>(w, h, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (input.count(x, y) == 0) continue;
      int nearest = *std::max_element(input.begin(x, y), input.end(x, y));
      frame.lidarSparse(x, y) = static_cast<std::int16_t>(nearest);
      frame.exclude(x, y) = 1;
    }
  }
}

double maxGroundTruth(const Image<float>& groundTruth) {
  double m = 0.0;
  for (int y = 0; y < groundTruth.height(); ++y) {
    for (int x = 0; x < groundTruth.width(); ++x) {
      const float d = groundTruth(x, y);
      if (d > 0.0f && std::isfinite(d)) m = std::max(m, static_cast<double>(d));
    }
  }
  return m;
}

namespace {

/// One P1 frame on disk.
struct P1Files {
  std::string dataset;
  std::string name;
  std::string left;
  std::string right;
  std::string groundTruth;
  int gtDivisor = 0;  ///< 0: KITTI 16-bit PNG (value/256); else 8-bit PNG, value/gtDivisor
  double focalBaseline = 0.0;
};

/// The stems of the files with `extension` in `dir`, sorted; empty when `dir` is absent.
std::vector<std::string> stems(const fs::path& dir, const std::string& extension) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == extension) out.push_back(e.path().stem().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

/// Frames whose left, right and GT files all exist: left/<id><ext>, right/<id><ext>, gt/<id>.png.
void addStereoFolder(std::vector<P1Files>& out, const fs::path& root, const std::string& dataset,
                     const std::string& leftDir, const std::string& rightDir, const std::string& gtDir,
                     const std::string& imageExt, double focalBaseline) {
  for (const std::string& id : stems(root / gtDir, ".png")) {
    const fs::path left = root / leftDir / (id + imageExt);
    const fs::path right = root / rightDir / (id + imageExt);
    if (!isFile(left) || !isFile(right)) continue;
    out.push_back({dataset, id, left.string(), right.string(), (root / gtDir / (id + ".png")).string(), 0,
                   focalBaseline});
  }
}

/// Middlebury scenes: 2003 quarter size (im2/im6/disp2, GT value/4) and 2005/6 half size
/// (view1/view5/disp1, GT value/2), per its SOURCE.md.
void addMiddlebury(std::vector<P1Files>& out, const fs::path& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return;
  for (const fs::directory_entry& e : fs::directory_iterator(root)) {
    if (!e.is_directory()) continue;
    const fs::path d = e.path();
    const std::string scene = d.filename().string();
    if (isFile(d / "im2.png") && isFile(d / "im6.png") && isFile(d / "disp2.png")) {
      out.push_back({"middlebury", scene, (d / "im2.png").string(), (d / "im6.png").string(),
                     (d / "disp2.png").string(), 4, kMiddleburyFocalBaseline});
    } else if (isFile(d / "view1.png") && isFile(d / "view5.png") && isFile(d / "disp1.png")) {
      out.push_back({"middlebury", scene, (d / "view1.png").string(), (d / "view5.png").string(),
                     (d / "disp1.png").string(), 2, kMiddleburyFocalBaseline});
    }
  }
}

/// 8-bit GT PNG, disparity = value / divisor, 0 = none.
Image<float> readScaledGroundTruth(const std::string& path, int divisor) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty()) throw std::runtime_error("cannot read ground truth " + path);
  if (raw.channels() != 1 || (raw.depth() != CV_8U && raw.depth() != CV_16U)) {
    throw std::runtime_error("ground truth " + path + " is not a single-channel 8- or 16-bit image");
  }
  cv::Mat values;
  raw.convertTo(values, CV_32F, 1.0 / divisor);
  Image<float> gt(raw.cols, raw.rows, 0.0f);
  for (int y = 0; y < raw.rows; ++y) {
    for (int x = 0; x < raw.cols; ++x) gt(x, y) = values.at<float>(y, x);
  }
  return gt;
}

EvalFrame loadP1Frame(const P1Files& f) {
  EvalFrame frame;
  frame.protocol = "P1";
  frame.dataset = f.dataset;
  frame.name = f.name;
  frame.left = io::readGrayImage(f.left);
  frame.right = io::readGrayImage(f.right);
  frame.leftColor = io::readColorImage(f.left);
  frame.groundTruth = f.gtDivisor == 0 ? io::readKittiDisparityFloat(f.groundTruth)
                                       : readScaledGroundTruth(f.groundTruth, f.gtDivisor);
  if (frame.left.size() != frame.right.size() || frame.left.depth() != frame.right.depth() ||
      frame.left.cols != frame.groundTruth.width() || frame.left.rows != frame.groundTruth.height()) {
    throw std::runtime_error("P1 " + f.dataset + "/" + f.name + ": left, right and ground truth differ in size (" +
                             f.left + ", " + f.right + ", " + f.groundTruth + ")");
  }
  // Exactly as tests/eval/test_kitti_p1.cpp: default options (HDL-64E-like rows for KITTI's
  // intrinsics scaled to the image width, every 2nd pixel, 0.1 px noise, seed 1).
  Image<std::uint8_t> inputMask;
  const LidarPoints lidar = eval::simulateLidarFromGroundTruth(frame.groundTruth.view(), {}, inputMask);
  setLidarInput(frame, lidar);  // exclude = the input pixels = the simulator's inputMask
  frame.focalBaseline = f.focalBaseline;
  frame.numDisparities = numDisparitiesFor(maxGroundTruth(frame.groundTruth));
  return frame;
}

}  // namespace

std::vector<EvalFrame> loadP1(const std::string& dataRoot) {
  const fs::path root(dataRoot);
  std::vector<P1Files> files;
  addStereoFolder(files, root / "kitti_stereo2015_training_sample", "kitti2015", "image_2", "image_3", "disp_occ_0",
                  ".png", kKittiFocalBaseline);
  addStereoFolder(files, root / "kitti_stereo2012_training_sample", "kitti2012", "colored_0", "colored_1", "disp_occ",
                  ".png", kKittiFocalBaseline);
  addStereoFolder(files, root / "drivingstereo_sample", "drivingstereo", "left", "right", "disparity", ".jpg",
                  kDrivingStereoFocalBaseline);
  addMiddlebury(files, root / "middlebury_stereo_sample");
  std::sort(files.begin(), files.end(), [](const P1Files& a, const P1Files& b) {
    return std::tie(a.dataset, a.name) < std::tie(b.dataset, b.name);
  });
  std::vector<EvalFrame> frames;
  frames.reserve(files.size());
  for (const P1Files& f : files) frames.push_back(loadP1Frame(f));
  return frames;
}

}  // namespace eval
}  // namespace lidar_sgm
