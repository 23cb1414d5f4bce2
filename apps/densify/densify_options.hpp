#pragma once
// What lidar_sgm_densify and lidar_sgm_batch share: the method's options (the matcher's, the
// output filters', the output's) and the one way they configure an SGMDensification, so that a
// frame densified by either tool is the same cloud, byte for byte.

#include <cstdint>
#include <set>
#include <string>

#include <opencv2/core.hpp>

#include "common/arguments.hpp"
#include "common/filter_options.hpp"
#include "common/sgm_options.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/pcl_image.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace apps {

/// The dense cloud's encoding, frame and sampling (-format, -frame, -max_depth, -stride, -voxel).
struct OutputOptions {
  io::CloudFormat format = io::CloudFormat::Binary;
  geometry::OutputFrame frame = geometry::OutputFrame::Lidar;
  double maxDepth = geometry::ReprojectionOptions().maxDepth;  ///< infinity for -max_depth 0
  int stride = 1;
  double voxel = 0;  ///< voxel edge [m] for pcl::VoxelGrid down-sampling; 0 = none
};

/// -format, -frame, -max_depth, -stride, -voxel, validated (std::invalid_argument names the bad one).
OutputOptions outputOptionsFrom(const Arguments& args);

/// "1242x375" -> (1242, 375); `option` names the option in errors.
void parseImageSize(const std::string& text, int& width, int& height, const char* option = "image_size");

/// Option names of the method and the cloud it writes: the matcher's, the output filters',
/// -format, -frame, -max_depth, -stride, -voxel, -image_size (values) and -keep_organized,
/// -no_occlusion_filter, -no_crop_to_scan (flags).
/// Throws std::invalid_argument naming `path` when `image` has fewer than 2 rows or columns: PCL
/// takes a cloud of height 1 for an unorganized one, so such an image cannot color a cloud.
void requireOrganizedImage(const std::string& path, const cv::Mat& image);

/// -max_points: the most points an input scan may hold (default io::kMaxCloudPoints).
std::uint64_t maxPointsFrom(const Arguments& args);

std::set<std::string> densifyValueOptions();
std::set<std::string> densifyFlagOptions();

/// The help lines of the cloud's options (-format, -keep_organized, -frame, -max_depth, -stride,
/// -voxel), of the filters (-min_confidence, -no_occlusion_filter, -no_crop_to_scan and the output
/// filters') and of the input's limit (-max_points), one help group each.
std::string outputOptionsHelp();
std::string densifyFilterOptionsHelp();
std::string inputLimitOptionsHelp();

/// Checks every method option before any file is read (std::invalid_argument names the bad one).
void checkDensifyOptions(const Arguments& args);

/// Sets everything the command line says on `sgm`: parameters, backend, disparity range mode,
/// projection, organisation, crop, confidence, filters, frame, depth and stride.
template <typename PointOutT>
void configureDensification(SGMDensification<pcl::PointXYZI, PointOutT>& sgm, const Arguments& args) {
  sgm.setParameters(parametersFrom(args));
  sgm.setBackend(backendFrom(args));
  sgm.setDisparityRangeMode(fixedDisparityRange(args) ? DisparityRangeMode::Fixed : DisparityRangeMode::FromLidar);
  geometry::ProjectionOptions projection;
  projection.occlusion.enabled = !args.has("no_occlusion_filter");
  sgm.setProjectionOptions(projection);
  sgm.setKeepOrganized(args.has("keep_organized"));
  sgm.setCropToScan(!args.has("no_crop_to_scan"));
  sgm.setMinConfidence(minConfidenceFrom(args));
  sgm.setOutputFilters(outputFiltersFrom(args));
  sgm.setPairCheck(pairCheckFrom(args));
  const OutputOptions out = outputOptionsFrom(args);
  sgm.setOutputFrame(out.frame);
  sgm.setMaxDepth(out.maxDepth);
  sgm.setStride(out.stride);
}

/// The images as decoded (empty when absent): a pair -> fused matching on their gray levels at
/// full depth (8 or 16 bit); `left` also colors the output.
template <typename PointOutT>
void setImages(SGMDensification<pcl::PointXYZI, PointOutT>& sgm, const cv::Mat& left, const cv::Mat& right) {
  if (!right.empty()) {
    const cv::Mat leftGray = io::toGray(left);
    const cv::Mat rightGray = io::toGray(right);
    if (leftGray.depth() != rightGray.depth()) {
      throw std::invalid_argument("the left and right images differ in bit depth (8 vs 16 bit)");
    }
    if (leftGray.depth() == CV_16U) {
      sgm.setStereoPair(io::grayView(leftGray).gray16, io::grayView(rightGray).gray16);
    } else {
      sgm.setStereoPair(io::grayView(leftGray).gray8, io::grayView(rightGray).gray8);
    }
  }
  if (!left.empty()) sgm.setColorImage(io::toPclImage(io::toColor(left)));
}

}  // namespace apps
}  // namespace lidar_sgm
