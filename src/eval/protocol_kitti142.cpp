// Protocol KITTI142: the paper's own real-data protocol (Sec. IV-A-a, Tables I and II): KITTI
// stereo 2015 training frames with the raw Velodyne scan of the same instant, scored against
// disp_occ_0 on every GT pixel, with the object map's background / foreground split.
#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_rings.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace eval {

namespace fs = std::filesystem;

namespace {

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

/// The frame ids (e.g. "000007_10") with every file the protocol needs, sorted.
std::vector<std::string> frameIds(const fs::path& root) {
  std::vector<std::string> ids;
  std::error_code ec;
  if (!fs::is_directory(root / "velodyne", ec)) return ids;
  for (const fs::directory_entry& e : fs::directory_iterator(root / "velodyne")) {
    if (!e.is_regular_file() || e.path().extension() != ".bin") continue;
    const std::string id = e.path().stem().string();
    const std::string png = id + ".png";
    if (isFile(root / "image_2" / png) && isFile(root / "image_3" / png) && isFile(root / "disp_occ_0" / png) &&
        isFile(root / "obj_map" / png)) {
      ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

EvalFrame loadFrame(const fs::path& root, const std::string& id, const geometry::StereoCalibration& calibration) {
  EvalFrame frame;
  frame.protocol = "KITTI142";
  frame.dataset = "kitti2015_lidar";
  frame.name = id;
  const std::string png = id + ".png";
  const std::string leftPath = (root / "image_2" / png).string();
  frame.left = io::readGrayImage(leftPath);
  frame.right = io::readGrayImage((root / "image_3" / png).string());
  frame.leftColor = io::readColorImage(leftPath);
  if (frame.left.cols != calibration.width || frame.left.rows != calibration.height ||
      frame.right.size() != frame.left.size()) {
    throw std::runtime_error("KITTI142 " + id + ": the images are not " + std::to_string(calibration.width) + "x" +
                             std::to_string(calibration.height) + " as the calibration");
  }
  frame.focalBaseline = calibration.focalBaseline();
  frame.calibration = calibration;  // the methods' clouds are scored in 3D against the GT's
  // The input: the whole raw scan, projected as the tools project it (default options, occlusion
  // filter on).
  const std::vector<Eigen::Vector3f> points = toPoints(io::readKittiBin((root / "velodyne" / (id + ".bin")).string()));
  setLidarInput(frame, geometry::project(points, calibration).lidarPoints());
  // Every GT pixel is scored (the paper's protocol); the input's pixels are kept apart for the
  // "no input point" figure.
  frame.inputPixels = frame.exclude;
  frame.exclude = Image<std::uint8_t>();
  frame.groundTruth = io::readKittiDisparityFloat((root / "disp_occ_0" / png).string());
  const cv::Mat objects = io::readImage((root / "obj_map" / png).string());
  if (objects.cols != calibration.width || objects.rows != calibration.height || objects.type() != CV_8UC1) {
    throw std::runtime_error("KITTI142 " + id + ": obj_map is not an 8-bit gray image of the frame's size");
  }
  frame.objectMap = Image<std::uint8_t>(objects.cols, objects.rows);
  for (int y = 0; y < objects.rows; ++y) {
    for (int x = 0; x < objects.cols; ++x) frame.objectMap(x, y) = objects.at<std::uint8_t>(y, x);
  }
  frame.numDisparities = numDisparitiesFor(maxGroundTruth(frame.groundTruth));
  return frame;
}

}  // namespace

std::vector<EvalFrame> loadKitti142(const std::string& dataRoot, int maxFrames) {
  const fs::path root = fs::path(dataRoot) / "kitti2015_lidar";
  std::vector<std::string> ids = frameIds(root);
  if (ids.empty()) return {};
  if (maxFrames > 0 && static_cast<int>(ids.size()) > maxFrames) ids.resize(static_cast<std::size_t>(maxFrames));
  const cv::Mat first = io::readGrayImage((root / "image_2" / (ids.front() + ".png")).string());
  // One calibration for every frame: all were recorded on 2011_09_26 (SOURCE.md).
  const geometry::StereoCalibration calibration =
      io::readCalibration((root / "calib" / "calib_cam_to_cam.txt").string(), first.cols, first.rows);
  std::vector<EvalFrame> frames;
  for (const std::string& id : ids) frames.push_back(loadFrame(root, id, calibration));
  return frames;
}

}  // namespace eval
}  // namespace lidar_sgm
