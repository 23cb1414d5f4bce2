#include "batch/map_picture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "lidar_sgm/io/color_map.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

struct Extent {
  double minX = std::numeric_limits<double>::infinity();
  double maxX = -std::numeric_limits<double>::infinity();
  double minZ = std::numeric_limits<double>::infinity();
  double maxZ = -std::numeric_limits<double>::infinity();
  void add(double x, double z) {
    minX = std::min(minX, x);
    maxX = std::max(maxX, x);
    minZ = std::min(minZ, z);
    maxZ = std::max(maxZ, z);
  }
};

}  // namespace

TopView renderTopView(const pcl::PointCloud<PointXYZRGBConfidence>& map, bool useColor,
                      const std::vector<Eigen::Vector3d>& trajectory, const TopViewOptions& options) {
  if (map.empty()) throw std::invalid_argument("the map has no point to draw");
  if (options.maxSide < 16 || options.margin < 0 || 2 * options.margin >= options.maxSide - 1 ||
      !(options.minMetresPerPixel > 0.0)) {
    throw std::invalid_argument("top view: needs maxSide >= 16, 0 <= 2 margin < maxSide - 1, minMetresPerPixel > 0");
  }
  Extent extent;
  double minHeight = std::numeric_limits<double>::infinity();
  double maxHeight = -minHeight;
  for (const PointXYZRGBConfidence& p : map) {
    extent.add(p.x, p.z);
    minHeight = std::min(minHeight, -static_cast<double>(p.y));  // y points down: height is -y
    maxHeight = std::max(maxHeight, -static_cast<double>(p.y));
  }
  for (const Eigen::Vector3d& position : trajectory) extent.add(position.x(), position.z());
  const double longSide = std::max(extent.maxX - extent.minX, extent.maxZ - extent.minZ);
  const int inner = options.maxSide - 2 * options.margin - 1;
  TopView view;
  view.metresPerPixel = std::max(longSide / inner, options.minMetresPerPixel);
  const auto column = [&](double x) {
    return options.margin + static_cast<int>(std::floor((x - extent.minX) / view.metresPerPixel));
  };
  const auto row = [&](double z) {  // forward is up
    return options.margin + static_cast<int>(std::floor((extent.maxZ - z) / view.metresPerPixel));
  };
  const int width = std::min(column(extent.maxX) + 1 + options.margin, options.maxSide);
  const int height = std::min(row(extent.minZ) + 1 + options.margin, options.maxSide);
  view.image = cv::Mat(height, width, CV_8UC3, cv::Scalar(0, 0, 0));

  cv::Mat top(height, width, CV_32FC1, cv::Scalar(-std::numeric_limits<float>::infinity()));
  const std::array<cv::Vec3b, 256>& turbo = io::turboColors();
  const double heightRange = maxHeight - minHeight;
  for (const PointXYZRGBConfidence& p : map) {
    const int u = std::min(column(p.x), width - 1);
    const int v = std::min(row(p.z), height - 1);
    const float h = -p.y;
    if (!(h > top.at<float>(v, u))) continue;
    top.at<float>(v, u) = h;
    if (useColor) {
      view.image.at<cv::Vec3b>(v, u) = cv::Vec3b(p.b, p.g, p.r);
    } else {
      const double t = heightRange > 0.0 ? (static_cast<double>(h) - minHeight) / heightRange : 0.5;
      view.image.at<cv::Vec3b>(v, u) = turbo[static_cast<std::size_t>(std::lround(255.0 * t))];
    }
  }
  std::vector<cv::Point> line;
  for (const Eigen::Vector3d& position : trajectory) line.emplace_back(column(position.x()), row(position.z()));
  if (line.size() == 1) line.push_back(line.front());  // one pose: a dot
  if (!line.empty()) cv::polylines(view.image, line, false, cv::Scalar(255, 255, 255), 2, cv::LINE_8);
  return view;
}

}  // namespace apps
}  // namespace lidar_sgm
