// densify(): an Open3D scan and images through the Densifier, the dense cloud back as Open3D's.
#include "lidar_sgm/open3d/densify.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace lidar_sgm {
namespace {

using Open3dImage = ::open3d::geometry::Image;
using Open3dCloud = ::open3d::geometry::PointCloud;

bool sameFormat(const Open3dImage& a, const Open3dImage& b) {
  return a.num_of_channels_ == b.num_of_channels_ && a.bytes_per_channel_ == b.bytes_per_channel_;
}

/// The scan in the Densifier's float points. Open3D keeps double coordinates; a scan read from
/// float data (KITTI .bin, PCD) converts back without loss.
std::vector<Eigen::Vector3f> scanPoints(const Open3dCloud& scan) {
  if (scan.points_.empty()) throw std::invalid_argument("densify: the scan (Open3D point cloud) is empty");
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.points_.size());
  for (const Eigen::Vector3d& p : scan.points_) points.push_back(p.cast<float>());
  return points;
}

std::shared_ptr<Open3dCloud> toOpen3dCloud(const Densifier& densifier, bool colored) {
  const geometry::DenseCloud& dense = densifier.cloud();
  auto cloud = std::make_shared<Open3dCloud>();
  cloud->points_.reserve(dense.size());
  for (const Eigen::Vector3f& p : dense.points) cloud->points_.push_back(p.cast<double>());
  if (colored) {
    cloud->colors_.reserve(dense.size());
    for (const geometry::PixelIndex& pixel : dense.pixels) {
      Rgb8 c;
      densifier.colorAt(pixel.x, pixel.y, c);
      // Open3D's colors are RGB in [0, 1].
      cloud->colors_.emplace_back(c.r / 255.0, c.g / 255.0, c.b / 255.0);
    }
  }
  return cloud;
}

}  // namespace

void setStereoPair(Densifier& densifier, const Open3dImage& left, const Open3dImage& right) {
  const Open3dGray leftGray(left);
  const Open3dGray rightGray(right);
  if (!sameFormat(left, right)) {
    throw std::invalid_argument("setStereoPair: the left and right Open3D images differ in format (" +
                                std::to_string(left.num_of_channels_) + " vs " + std::to_string(right.num_of_channels_) +
                                " channel(s), " + std::to_string(left.bytes_per_channel_) + " vs " +
                                std::to_string(right.bytes_per_channel_) + " byte(s) per channel)");
  }
  // The Densifier checks the sizes (and names them).
  densifier.setStereoPair(leftGray.view(), rightGray.view());
  const Image<Rgb8> color = toRgb8(left);
  densifier.setColorImage(color.view());
}

std::shared_ptr<Open3dCloud> densify(Densifier& densifier, const Open3dCloud& scan, const Open3dImage* left,
                                     const Open3dImage* right) {
  if (right && !left) throw std::invalid_argument("densify: a right image needs the left one");
  const std::vector<Eigen::Vector3f> points = scanPoints(scan);
  if (right) {
    setStereoPair(densifier, *left, *right);
  } else {
    densifier.clearStereoPair();
    if (left) {
      const Image<Rgb8> color = toRgb8(*left);
      densifier.setColorImage(color.view());
    } else {
      densifier.setColorImage(ImageView<const Rgb8>());
    }
  }
  densifier.run(points);
  return toOpen3dCloud(densifier, left != nullptr);
}

std::shared_ptr<Open3dCloud> densify(const Open3dCloud& scan, const geometry::StereoCalibration& calibration,
                                     const Open3dImage* left, const Open3dImage* right, const Parameters& parameters) {
  Densifier densifier;
  densifier.setCalibration(calibration);
  densifier.setParameters(parameters);
  return densify(densifier, scan, left, right);
}

}  // namespace lidar_sgm
