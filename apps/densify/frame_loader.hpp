#pragma once
// One frame's inputs read and checked, the same way for lidar_sgm_densify and lidar_sgm_batch:
// the scan, the calibration, the pair, in that order, each refused with a message naming it.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace apps {

/// The files of one frame; `left`/`right` empty when absent.
struct FrameFiles {
  std::string scan;
  std::string calib;
  std::string left;
  std::string right;
  int width = 0;   ///< -image_size (0: from the calibration or the images); the calibration must agree
  int height = 0;
  std::uint64_t maxPoints = 0;  ///< -max_points
  /// How `calib` is read (path, width, height): io::readCalibration unless the layout says otherwise.
  std::function<geometry::StereoCalibration(const std::string&, int, int)> readCalibration;
};

struct LoadedFrame {
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan;
  geometry::StereoCalibration calibration;
  cv::Mat left;   ///< as stored (8 or 16 bits, gray or color); empty when absent
  cv::Mat right;
};

/// Reads and checks `files`: a scan with points, a calibration that agrees with -image_size,
/// a right image only with a left one of the same size, an organized left image. Throws
/// (std::exception) naming the file and the problem. With `log`, one line per file as
/// lidar_sgm_densify prints them ("Loading PATH [done, N ms : what was read]").
LoadedFrame loadFrame(const FrameFiles& files, std::FILE* log = nullptr);

}  // namespace apps
}  // namespace lidar_sgm
