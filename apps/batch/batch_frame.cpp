#include "batch/batch_frame.hpp"

#include <filesystem>
#include <stdexcept>
#include <utility>

#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "common/timer.hpp"
#include "densify/densify_options.hpp"
#include "densify/frame_loader.hpp"
#include "densify/voxel_filter.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

/// lidar_sgm_densify's loading (loadFrame), then the sequence's image size.
LoadedFrame load(const sequence::Frame& frame, int width, int height, std::uint64_t maxPoints,
               const std::map<std::string, CalibrationImage>& shared) {
  FrameFiles files;
  files.scan = frame.scan;
  files.calib = frame.calib;
  files.left = frame.left;
  files.right = frame.right;
  files.width = width;
  files.height = height;
  files.maxPoints = maxPoints;
  files.readCalibration = [&frame](const std::string&, int w, int h) {
    return sequence::readFrameCalibration(frame, w, h);
  };
  LoadedFrame data = loadFrame(files);
  const auto sequenceSize = shared.find(frame.calib);
  if (sequenceSize != shared.end() && data.calibration.width == 0 && data.calibration.height == 0) {
    const CalibrationImage& size = sequenceSize->second;
    if (!data.left.empty() && (data.left.cols != size.width || data.left.rows != size.height)) {
      throw std::invalid_argument("the left image '" + frame.left + "' is " + sizeText(data.left.cols, data.left.rows) +
                                  " but the calibration '" + frame.calib + "' is the sequence's, whose images are " +
                                  sizeText(size.width, size.height) + " ('" + size.image +
                                  "'): its intrinsics do not fit this frame");
    }
    data.calibration.width = size.width;
    data.calibration.height = size.height;
  }
  return data;
}

template <typename PointOutT>
FrameResult densifyWith(SGMDensification<pcl::PointXYZI, PointOutT>& sgm, const DensifierConfig& config,
                        const OutputOptions& out, const LoadedFrame& data, const std::string& outPath,
                        sequence::FrameTimings ms) {
  sgm.setInputCloud(data.scan);
  sgm.setCalibration(data.calibration);
  sgm.setConfig(config);
  setImages(sgm, data.left, data.right);
  pcl::PointCloud<PointOutT> dense;
  sgm.filter(dense);
  if (!sgm.getLastError().empty()) throw std::runtime_error(sgm.getLastError());
  if (dense.empty()) throw std::runtime_error("the dense cloud is empty: no pixel has a disparity within -max_depth");
  ms.project = sgm.getTimings().project;
  ms.match = sgm.getTimings().match;
  ms.reproject = sgm.getTimings().reproject;
  const Timer saveTimer;
  voxelDownsample(dense, out.voxel);
  io::writeCloud(outPath, dense, out.format);
  ms.save = saveTimer.elapsedMs();
  return {dense.size(), std::filesystem::file_size(outPath), ms};
}

}  // namespace

std::map<std::string, CalibrationImage> sharedCalibrationImages(const std::vector<sequence::Frame>& frames) {
  std::map<std::string, int> uses;
  for (const sequence::Frame& frame : frames) ++uses[frame.calib];
  std::map<std::string, CalibrationImage> sizes;
  for (const sequence::Frame& frame : frames) {
    if (frame.left.empty() || uses[frame.calib] < 2 || sizes.count(frame.calib) > 0) continue;
    try {
      // A PNG's size comes from its header: the frame decodes the image again when it runs.
      const cv::Size size = io::imageSize(frame.left);
      sizes[frame.calib] = {size.width, size.height, frame.left};
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

FrameDensifier::FrameDensifier(const Arguments& args, const DensifierConfig& config, int width, int height,
                               int threads, std::map<std::string, CalibrationImage> shared)
    : config_(config), out_(outputOptionsFrom(args)), maxPoints_(maxPointsFrom(args)), width_(width), height_(height),
      shared_(std::move(shared)), densifications_(std::make_unique<Densifications>()) {
  config_.matcher.threads = threads;
}

FrameDensifier::~FrameDensifier() = default;

FrameResult FrameDensifier::densify(const sequence::Frame& frame, const std::string& outPath) {
  const Timer loadTimer;
  const LoadedFrame data = load(frame, width_, height_, maxPoints_, shared_);
  sequence::FrameTimings ms;
  ms.load = loadTimer.elapsedMs();
  Densifications& d = *densifications_;
  if (!config_.matcher.confidence) {
    return data.left.empty() ? densifyWith(Densifications::get(d.xyz), config_, out_, data, outPath, ms)
                             : densifyWith(Densifications::get(d.rgb), config_, out_, data, outPath, ms);
  }
  return data.left.empty() ? densifyWith(Densifications::get(d.xyzConfidence), config_, out_, data, outPath, ms)
                           : densifyWith(Densifications::get(d.rgbConfidence), config_, out_, data, outPath, ms);
}

}  // namespace apps
}  // namespace lidar_sgm
