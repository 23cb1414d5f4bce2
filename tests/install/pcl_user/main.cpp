// Downstream use of lidar_sgm::pcl and lidar_sgm::io from an installed package: fused LiDAR-SGM on
// the bundled sample frame (data/sample), checked against its exact ground-truth disparity.
// Usage: pcl_user SAMPLE_DIR. Exits non-zero when the result is wrong.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <lidar_sgm/io/calibration_io.hpp>
#include <lidar_sgm/io/cloud_io.hpp>
#include <lidar_sgm/io/image_io.hpp>
#include <lidar_sgm/io/pcl_image.hpp>
#include <lidar_sgm/pcl/sgm_densification.hpp>

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SAMPLE_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = std::string(argv[1]) + "/";
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan(
      new pcl::PointCloud<pcl::PointXYZI>(lidar_sgm::io::readCloud(dir + "velodyne/000000.bin")));
  const cv::Mat left = lidar_sgm::io::readColorImage(dir + "image_2/000000.png");
  const cv::Mat right = lidar_sgm::io::readColorImage(dir + "image_3/000000.png");

  lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
  sgm.setInputCloud(scan);
  sgm.setCalibration(lidar_sgm::io::readCalibration(dir + "calib/000000.txt", left.cols, left.rows));
  sgm.setStereoPair(lidar_sgm::io::toPclImage(left), lidar_sgm::io::toPclImage(right));
  sgm.setAlpha(0.7f);
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  if (!sgm.getLastError().empty()) {
    std::fprintf(stderr, "FAILED: %s\n", sgm.getLastError().c_str());
    return 1;
  }

  // Against the exact ground truth: share of GT pixels estimated within 3 px (KITTI's threshold).
  const lidar_sgm::Image<std::int16_t> gt = lidar_sgm::io::readKittiDisparity(dir + "disp_gt/000000.png");
  const lidar_sgm::Image<std::int16_t>& estimate = sgm.getDisparityImage();
  if (estimate.width() != gt.width() || estimate.height() != gt.height()) {
    std::fprintf(stderr, "FAILED: disparity %dx%d, ground truth %dx%d\n", estimate.width(), estimate.height(),
                 gt.width(), gt.height());
    return 1;
  }
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
  std::printf("scan %zu points -> dense %zu points; %.3f of %ld ground-truth pixels within 3 px\n", scan->size(),
              dense.size(), share, total);
  if (dense.size() < 5 * scan->size() || share < 0.8) {
    std::fprintf(stderr, "FAILED: expected >= 5x the scan's points and >= 0.8 within 3 px\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "FAILED: %s\n", e.what());
  return 1;
}
