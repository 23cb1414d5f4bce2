// Protocol P2: real LiDAR, ring (or image row) hold-out.
#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_rings.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"

namespace lidar_sgm {
namespace eval {

namespace fs = std::filesystem;

RingSplit splitByRing(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& rings, int period,
                      int phase) {
  if (points.size() != rings.size()) throw std::invalid_argument("splitByRing: one ring per point expected");
  if (period < 1 || phase < 0 || phase >= period) {
    throw std::invalid_argument("splitByRing: period must be >= 1 and phase in [0, period)");
  }
  RingSplit split;
  for (std::size_t i = 0; i < points.size(); ++i) {
    split.rings = std::max(split.rings, rings[i] + 1);
    if (rings[i] % period == phase) {
      split.heldOut.push_back(points[i]);
      split.heldOutRings.push_back(rings[i]);
      split.heldOutIndex.push_back(i);
    } else {
      split.input.push_back(points[i]);
      split.inputRings.push_back(rings[i]);
    }
  }
  return split;
}

void splitSparseRows(const Image<std::int16_t>& sparse, Image<std::int16_t>& input, Image<std::int16_t>& heldOut,
                     int minPointsPerRow, int period, int phase) {
  if (period < 1 || phase < 0 || phase >= period) {
    throw std::invalid_argument("splitSparseRows: period must be >= 1 and phase in [0, period)");
  }
  const int w = sparse.width();
  const int h = sparse.height();
  input = Image<std::int16_t>(w, h, kInvalidDisparity);
  heldOut = Image<std::int16_t>(w, h, kInvalidDisparity);
  int beamRow = 0;  // index among the rows with >= minPointsPerRow points
  for (int y = 0; y < h; ++y) {
    int count = 0;
    for (int x = 0; x < w; ++x) count += sparse(x, y) != kInvalidDisparity && sparse(x, y) > 0;
    bool hold = false;
    if (count >= minPointsPerRow) {
      hold = beamRow % period == phase;
      ++beamRow;
    }
    Image<std::int16_t>& target = hold ? heldOut : input;
    for (int x = 0; x < w; ++x) {
      if (sparse(x, y) != kInvalidDisparity && sparse(x, y) > 0) target(x, y) = sparse(x, y);
    }
  }
}

namespace {

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

double maxInput(const LidarPoints& lidar) {
  int m = 0;
  for (int y = 0; y < lidar.height(); ++y) {
    for (int x = 0; x < lidar.width(); ++x) {
      for (const int* d = lidar.begin(x, y); d != lidar.end(x, y); ++d) m = std::max(m, *d);
    }
  }
  return static_cast<double>(m) / kDisparityScale;
}

void checkPair(const EvalFrame& f, const std::string& where) {
  if (f.left.empty() || f.left.size() != f.right.size() || f.left.depth() != f.right.depth()) {
    throw std::runtime_error("P2 " + where + ": left and right images differ in size or depth");
  }
}

/// kitti_stereo_lidar_calib_nogt/<frame>: ring hold-out on the raw scan.
EvalFrame loadRingFrame(const fs::path& root, const std::string& id) {
  EvalFrame frame;
  frame.protocol = "P2";
  frame.dataset = "kitti_lidar";
  frame.name = id;
  const std::string leftPath = (root / "image_2" / (id + ".png")).string();
  frame.left = io::readGrayImage(leftPath);
  frame.right = io::readGrayImage((root / "image_3" / (id + ".png")).string());
  frame.leftColor = io::readColorImage(leftPath);
  checkPair(frame, id);
  const geometry::StereoCalibration calibration =
      io::readCalibration((root / "calib" / (id + ".txt")).string(), frame.left.cols, frame.left.rows);
  frame.focalBaseline = calibration.focalBaseline();

  const std::vector<Eigen::Vector3f> points = toPoints(io::readKittiScan((root / "velodyne" / (id + ".bin")).string()));
  const std::vector<int> rings = recoverRings(points);
  const RingSplit split = splitByRing(points, rings);

  // Input: what a user feeding these rings gets (default projection, occlusion filter on).
  const geometry::ProjectedLidar input = geometry::project(split.input, calibration);
  setLidarInput(frame, input.lidarPoints());

  // GT: the held-out points that survive the projection of the whole scan (see protocols.hpp),
  // nearest per pixel.
  const geometry::ProjectedLidar all = geometry::project(points, calibration);
  frame.groundTruth = Image<float>(calibration.width, calibration.height, 0.0f);
  for (std::size_t i = 0; i < all.samples.size(); ++i) {
    if (rings[all.sourceIndex[i]] % 4 != 3) continue;
    const LidarSample& s = all.samples[i];
    float& gt = frame.groundTruth(s.x, s.y);
    gt = std::max(gt, static_cast<float>(s.disparity16) / kDisparityScale);
  }
  frame.numDisparities = numDisparitiesFor(std::max(maxGroundTruth(frame.groundTruth), maxInput(frame.lidar)));
  return frame;
}

/// kitti_stereo_sparse_lidar_disparity_sample: row hold-out on the projected scan.
EvalFrame loadSparseFrame(const fs::path& root) {
  EvalFrame frame;
  frame.protocol = "P2";
  frame.dataset = "kitti_sparse";
  frame.name = "sample";
  const std::string leftPath = (root / "left.png").string();
  frame.left = io::readGrayImage(leftPath);
  frame.right = io::readGrayImage((root / "right.png").string());
  frame.leftColor = io::readColorImage(leftPath);
  checkPair(frame, "kitti_sparse");
  const std::string sparsePath = (root / "sparse_lidar_disparity.png").string();
  const Image<std::int16_t> sparse = io::readKittiDisparity(sparsePath);
  const Image<float> sparseFloat = io::readKittiDisparityFloat(sparsePath);
  if (sparse.width() != frame.left.cols || sparse.height() != frame.left.rows) {
    throw std::runtime_error("P2 " + sparsePath + " differs in size from the images");
  }
  Image<std::int16_t> input;
  Image<std::int16_t> heldOut;
  splitSparseRows(sparse, input, heldOut);
  setLidarInput(frame, LidarPoints::fromDisparityImage(input.view()));
  frame.groundTruth = Image<float>(sparse.width(), sparse.height(), 0.0f);
  for (int y = 0; y < sparse.height(); ++y) {
    for (int x = 0; x < sparse.width(); ++x) {
      if (heldOut(x, y) != kInvalidDisparity) frame.groundTruth(x, y) = sparseFloat(x, y);
    }
  }
  frame.focalBaseline = kKittiFocalBaseline;
  frame.numDisparities = numDisparitiesFor(std::max(maxGroundTruth(frame.groundTruth), maxInput(frame.lidar)));
  return frame;
}

}  // namespace

std::vector<EvalFrame> loadP2(const std::string& dataRoot) {
  std::vector<EvalFrame> frames;
  const fs::path ringRoot = fs::path(dataRoot) / "kitti_stereo_lidar_calib_nogt";
  std::error_code ec;
  if (fs::is_directory(ringRoot / "velodyne", ec)) {
    std::vector<std::string> ids;
    for (const fs::directory_entry& e : fs::directory_iterator(ringRoot / "velodyne")) {
      if (!e.is_regular_file() || e.path().extension() != ".bin") continue;
      const std::string id = e.path().stem().string();
      if (isFile(ringRoot / "calib" / (id + ".txt")) && isFile(ringRoot / "image_2" / (id + ".png")) &&
          isFile(ringRoot / "image_3" / (id + ".png"))) {
        ids.push_back(id);
      }
    }
    std::sort(ids.begin(), ids.end());
    for (const std::string& id : ids) frames.push_back(loadRingFrame(ringRoot, id));
  }
  const fs::path sparseRoot = fs::path(dataRoot) / "kitti_stereo_sparse_lidar_disparity_sample";
  if (isFile(sparseRoot / "left.png") && isFile(sparseRoot / "right.png") &&
      isFile(sparseRoot / "sparse_lidar_disparity.png")) {
    frames.push_back(loadSparseFrame(sparseRoot));
  }
  // "kitti_lidar" < "kitti_sparse": already in dataset, then name order.
  return frames;
}

}  // namespace eval
}  // namespace lidar_sgm
