#include "batch/batch_frame.hpp"

#include <filesystem>
#include <stdexcept>
#include <utility>

#include "batch/frame_calibration.hpp"
#include "common/timer.hpp"
#include "densify/densify_options.hpp"
#include "densify/voxel_filter.hpp"
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

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// The checks of lidar_sgm_densify's loading, in its order, and the sequence's image size.
FrameData load(const Frame& frame, int width, int height, std::uint64_t maxPoints,
               const std::map<std::string, CalibrationImage>& shared) {
  FrameData data;
  data.scan.reset(new pcl::PointCloud<pcl::PointXYZI>(io::readCloud(frame.scan, maxPoints)));
  if (data.scan->empty()) throw std::invalid_argument("the input cloud '" + frame.scan + "' has no points");
  data.calibration = readFrameCalibration(frame, width, height);
  if (width > 0 && (data.calibration.width != width || data.calibration.height != height)) {
    throw std::invalid_argument("-image_size " + sizeText(width, height) + " disagrees with the calibration '" +
                                frame.calib + "', which is for " +
                                sizeText(data.calibration.width, data.calibration.height));
  }
  if (!frame.left.empty()) {
    data.left = io::readImage(frame.left);
    requireOrganizedImage(frame.left, data.left);
  }
  const auto sequence = shared.find(frame.calib);
  if (sequence != shared.end() && data.calibration.width == 0 && data.calibration.height == 0) {
    const CalibrationImage& size = sequence->second;
    if (!data.left.empty() && (data.left.cols != size.width || data.left.rows != size.height)) {
      throw std::invalid_argument("the left image '" + frame.left + "' is " + sizeText(data.left.cols, data.left.rows) +
                                  " but the calibration '" + frame.calib + "' is the sequence's, whose images are " +
                                  sizeText(size.width, size.height) + " ('" + size.image +
                                  "'): its intrinsics do not fit this frame");
    }
    data.calibration.width = size.width;
    data.calibration.height = size.height;
  }
  if (!frame.left.empty() && !frame.right.empty()) {
    data.right = io::readImage(frame.right);
    if (data.right.size() != data.left.size()) {
      throw std::invalid_argument("the left image '" + frame.left + "' is " + sizeText(data.left.cols, data.left.rows) +
                                  " but the right image is " + sizeText(data.right.cols, data.right.rows));
    }
  }
  return data;
}

template <typename PointOutT>
FrameResult densifyWith(SGMDensification<pcl::PointXYZI, PointOutT>& sgm, const Arguments& args, int threads,
                        const FrameData& data, const std::string& outPath, FrameTimings ms) {
  sgm.setInputCloud(data.scan);
  sgm.setCalibration(data.calibration);
  configureDensification(sgm, args);
  Parameters params = sgm.getParameters();
  params.threads = threads;
  sgm.setParameters(params);
  setImages(sgm, data.left, data.right);
  pcl::PointCloud<PointOutT> dense;
  sgm.filter(dense);
  if (!sgm.getLastError().empty()) throw std::runtime_error(sgm.getLastError());
  if (dense.empty()) throw std::runtime_error("the dense cloud is empty: no pixel has a disparity within -max_depth");
  ms.project = sgm.getTimings().project;
  ms.match = sgm.getTimings().match;
  ms.reproject = sgm.getTimings().reproject;
  const Timer saveTimer;
  const OutputOptions out = outputOptionsFrom(args);
  voxelDownsample(dense, out.voxel);
  io::writeCloud(outPath, dense, out.format);
  ms.save = saveTimer.elapsedMs();
  return {dense.size(), std::filesystem::file_size(outPath), ms};
}

}  // namespace

std::map<std::string, CalibrationImage> sharedCalibrationImages(const std::vector<Frame>& frames) {
  std::map<std::string, int> uses;
  for (const Frame& frame : frames) ++uses[frame.calib];
  std::map<std::string, CalibrationImage> sizes;
  for (const Frame& frame : frames) {
    if (frame.left.empty() || uses[frame.calib] < 2 || sizes.count(frame.calib) > 0) continue;
    try {
      const cv::Mat image = io::readImage(frame.left);
      sizes[frame.calib] = {image.cols, image.rows, frame.left};
    } catch (const std::exception&) {
      // An unreadable image fails its own frame; the next one gives the size.
    }
  }
  return sizes;
}

/// The point types lidar_sgm_densify picks: colored when an image can color it, with the
/// confidence field unless it is off. Each is created on first use and kept.
struct FrameDensifier::Densifications {
  std::unique_ptr<SGMDensification<pcl::PointXYZI, pcl::PointXYZ>> xyz;
  std::unique_ptr<SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>> rgb;
  std::unique_ptr<SGMDensification<pcl::PointXYZI, PointXYZConfidence>> xyzConfidence;
  std::unique_ptr<SGMDensification<pcl::PointXYZI, PointXYZRGBConfidence>> rgbConfidence;

  template <typename PointOutT>
  static SGMDensification<pcl::PointXYZI, PointOutT>& get(
      std::unique_ptr<SGMDensification<pcl::PointXYZI, PointOutT>>& slot) {
    if (!slot) slot = std::make_unique<SGMDensification<pcl::PointXYZI, PointOutT>>();
    return *slot;
  }
};

FrameDensifier::FrameDensifier(const Arguments& args, int width, int height, int threads,
                               std::map<std::string, CalibrationImage> shared)
    : args_(args), width_(width), height_(height), threads_(threads), shared_(std::move(shared)),
      densifications_(std::make_unique<Densifications>()) {}

FrameDensifier::~FrameDensifier() = default;

FrameResult FrameDensifier::densify(const Frame& frame, const std::string& outPath) {
  const Timer loadTimer;
  const FrameData data = load(frame, width_, height_, maxPointsFrom(args_), shared_);
  FrameTimings ms;
  ms.load = loadTimer.elapsedMs();
  Densifications& d = *densifications_;
  if (args_.has("no_confidence")) {
    return data.left.empty() ? densifyWith(Densifications::get(d.xyz), args_, threads_, data, outPath, ms)
                             : densifyWith(Densifications::get(d.rgb), args_, threads_, data, outPath, ms);
  }
  return data.left.empty() ? densifyWith(Densifications::get(d.xyzConfidence), args_, threads_, data, outPath, ms)
                           : densifyWith(Densifications::get(d.rgbConfidence), args_, threads_, data, outPath, ms);
}

}  // namespace apps
}  // namespace lidar_sgm
