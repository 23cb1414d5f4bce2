#pragma once
// What lidar_sgm_densify and lidar_sgm_batch share: the option table's options plus their own
// (the cloud file's encoding, the down-sampling, the input's limits), and the one way they hand
// images to an SGMDensification, so that a frame densified by either tool is the same cloud.

#include <cstdint>
#include <set>
#include <string>

#include <opencv2/core.hpp>

#include "common/arguments.hpp"
#include "common/config_arguments.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/pcl_image.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace apps {

/// What the tools do with the dense cloud after the Densifier: its file encoding (-format) and
/// the down-sampling (-voxel). The cloud's frame, depth, stride and organisation are the
/// Densifier's (the option table's Output group).
struct OutputOptions {
  io::CloudFormat format = io::CloudFormat::Binary;
  double voxel = 0;  ///< voxel edge [m] for pcl::VoxelGrid down-sampling; 0 = none
};

/// -format and -voxel, validated (std::invalid_argument names the bad one).
OutputOptions outputOptionsFrom(const Arguments& args);

/// "1242x375" -> (1242, 375); `option` names the option in errors.
void parseImageSize(const std::string& text, int& width, int& height, const char* option = "image_size");

/// Throws std::invalid_argument naming `path` when `image` has fewer than 2 rows or columns: PCL
/// takes a cloud of height 1 for an unorganized one, so such an image cannot color a cloud.
void requireOrganizedImage(const std::string& path, const cv::Mat& image);

/// -max_points: the most points an input scan may hold (default io::kMaxCloudPoints).
std::uint64_t maxPointsFrom(const Arguments& args);

/// Option names of lidar_sgm_densify and lidar_sgm_batch: the option table's (every scope) and
/// -format, -voxel, -image_size, -max_points.
std::set<std::string> densifyValueOptions();
std::set<std::string> densifyFlagOptions();

/// The help lines of the cloud's options (-format, the table's Output group, -voxel) and of the
/// input's limit (-max_points).
std::string outputOptionsHelp();
std::string inputLimitOptionsHelp();

/// The Densifier's configuration from the command line, after checking the tool's own options
/// too, before any file is read (std::invalid_argument names the bad one).
DensifierConfig checkedDensifyOptions(const Arguments& args);

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
