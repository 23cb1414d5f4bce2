// Downstream use of lidar_sgm::open3d from an installed package: fused LiDAR-SGM on the bundled
// sample frame (data/sample) read by Open3D, checked against its exact ground-truth disparity.
// Usage: open3d_user SAMPLE_DIR. Exits non-zero when the result is wrong.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <open3d/geometry/PointCloud.h>
#include <open3d/io/ImageIO.h>

#include <lidar_sgm/io/calibration_io.hpp>
#include <lidar_sgm/io/image_io.hpp>
#include <lidar_sgm/open3d/densify.hpp>

namespace {

// A KITTI .bin scan: x, y, z, reflectance as float32 per point.
open3d::geometry::PointCloud readKittiBin(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  open3d::geometry::PointCloud scan;
  float p[4];
  while (in.read(reinterpret_cast<char*>(p), sizeof(p))) scan.points_.emplace_back(p[0], p[1], p[2]);
  return scan;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SAMPLE_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = std::string(argv[1]) + "/";
  const open3d::geometry::PointCloud scan = readKittiBin(dir + "velodyne/000000.bin");
  const auto left = open3d::io::CreateImageFromFile(dir + "image_2/000000.png");
  const auto right = open3d::io::CreateImageFromFile(dir + "image_3/000000.png");

  lidar_sgm::Densifier densifier;  // the Densifier variant keeps the disparity for the check
  densifier.setCalibration(lidar_sgm::io::readCalibration(dir + "calib/000000.txt", left->width_, left->height_));
  const std::shared_ptr<open3d::geometry::PointCloud> dense = lidar_sgm::densify(densifier, scan, left.get(), right.get());

  const lidar_sgm::Image<std::int16_t> gt = lidar_sgm::io::readKittiDisparity(dir + "disp_gt/000000.png");
  const lidar_sgm::Image<std::int16_t>& estimate = densifier.disparity();
  long total = 0;
  long correct = 0;
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      if (gt(x, y) == lidar_sgm::kInvalidDisparity || gt(x, y) <= 0) continue;
      ++total;
      const int d16 = estimate(x, y);
      if (d16 != lidar_sgm::kInvalidDisparity && std::abs(d16 - gt(x, y)) <= 3 * 16) ++correct;
    }
  }
  const double share = total > 0 ? static_cast<double>(correct) / total : 0.0;
  std::printf("scan %zu points -> dense %zu points (colors: %s); %.3f of %ld ground-truth pixels within 3 px\n",
              scan.points_.size(), dense->points_.size(), dense->HasColors() ? "yes" : "no", share, total);
  if (dense->points_.size() < 5 * scan.points_.size() || !dense->HasColors() || share < 0.8) {
    std::fprintf(stderr, "FAILED: expected >= 5x the scan's points, colors and >= 0.8 within 3 px\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "FAILED: %s\n", e.what());
  return 1;
}
