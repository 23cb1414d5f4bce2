#include "batch/batch_frame.hpp"

#include <stdexcept>

#include "batch/frame_calibration.hpp"
#include "common/timer.hpp"
#include "densify/densify_options.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

struct FrameData {
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan;
  geometry::StereoCalibration calibration;
  cv::Mat left;
  cv::Mat right;
};

/// The checks of lidar_sgm_densify's loading, in its order.
FrameData load(const Frame& frame, int width, int height) {
  FrameData data;
  data.scan.reset(new pcl::PointCloud<pcl::PointXYZI>(io::readCloud(frame.scan)));
  if (data.scan->empty()) throw std::invalid_argument("the input cloud '" + frame.scan + "' has no points");
  data.calibration = readFrameCalibration(frame, width, height);
  if (width > 0 && (data.calibration.width != width || data.calibration.height != height)) {
    throw std::invalid_argument("-image_size " + std::to_string(width) + "x" + std::to_string(height) +
                                " disagrees with the calibration '" + frame.calib + "', which is for " +
                                std::to_string(data.calibration.width) + "x" +
                                std::to_string(data.calibration.height));
  }
  if (!frame.left.empty()) {
    data.left = io::readImage(frame.left);
    if (!frame.right.empty()) {
      data.right = io::readImage(frame.right);
      if (data.right.size() != data.left.size()) {
        throw std::invalid_argument("the left image '" + frame.left + "' is " + std::to_string(data.left.cols) +
                                    "x" + std::to_string(data.left.rows) + " but the right image is " +
                                    std::to_string(data.right.cols) + "x" + std::to_string(data.right.rows));
      }
    }
  }
  return data;
}

template <typename PointOutT>
FrameResult densify(const Arguments& args, const FrameData& data, const std::string& outPath, FrameTimings ms) {
  SGMDensification<pcl::PointXYZI, PointOutT> sgm;
  sgm.setInputCloud(data.scan);
  sgm.setCalibration(data.calibration);
  configureDensification(sgm, args);
  setImages(sgm, data.left, data.right);
  pcl::PointCloud<PointOutT> dense;
  sgm.filter(dense);
  if (!sgm.getLastError().empty()) throw std::runtime_error(sgm.getLastError());
  if (dense.empty()) throw std::runtime_error("the dense cloud is empty: no pixel has a disparity within -max_depth");
  ms.project = sgm.getTimings().project;
  ms.match = sgm.getTimings().match;
  ms.reproject = sgm.getTimings().reproject;
  const Timer saveTimer;
  io::writeCloud(outPath, dense, outputOptionsFrom(args).format);
  ms.save = saveTimer.elapsedMs();
  return {dense.size(), ms};
}

}  // namespace

FrameResult densifyFrame(const Arguments& args, const Frame& frame, const std::string& outPath, int width,
                         int height) {
  const Timer loadTimer;
  const FrameData data = load(frame, width, height);
  FrameTimings ms;
  ms.load = loadTimer.elapsedMs();
  // The point type lidar_sgm_densify picks: colored when an image can color it, with the
  // confidence field unless it is off.
  if (args.has("no_confidence")) {
    return data.left.empty() ? densify<pcl::PointXYZ>(args, data, outPath, ms)
                             : densify<pcl::PointXYZRGB>(args, data, outPath, ms);
  }
  return data.left.empty() ? densify<PointXYZConfidence>(args, data, outPath, ms)
                           : densify<PointXYZRGBConfidence>(args, data, outPath, ms);
}

}  // namespace apps
}  // namespace lidar_sgm
