#include "lidar_sgm/io/sparse_lidar_check.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "lidar_sgm/core/lidar_points.hpp"

namespace lidar_sgm {
namespace io {
namespace {

constexpr double kDepthLikeTrend = 0.8;  ///< below: the values shrink toward the ground
constexpr std::size_t kMinPixelsPerThird = 100;

enum class NamedKind { Neither, Depth, Disparity };

/// What the path names: the file's name, else the nearest of its 3 folders that says "depth" or
/// "disp" (KITTI depth completion keeps the kind in a folder: proj_depth/velodyne_raw/image_02/).
/// A name with both says nothing.
NamedKind namedKind(const std::string& path) {
  std::filesystem::path p(path);
  for (int level = 0; level < 4 && !p.empty(); ++level, p = p.parent_path()) {
    std::string name = p.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool depth = name.find("depth") != std::string::npos;
    const bool disparity = name.find("disp") != std::string::npos;
    if (depth != disparity) return depth ? NamedKind::Depth : NamedKind::Disparity;
    if (depth) return NamedKind::Neither;
  }
  return NamedKind::Neither;
}

double median(std::vector<std::int16_t>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

std::string fixed(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", value);
  return text;
}

}  // namespace

double rowTrend(ImageView<const std::int16_t> d) {
  int first = -1;
  int last = -1;
  for (int y = 0; y < d.height; ++y) {
    for (int x = 0; x < d.width; ++x) {
      if (d(x, y) == kInvalidDisparity || d(x, y) <= 0) continue;
      if (first < 0) first = y;
      last = y;
      break;
    }
  }
  if (first < 0) return 0.0;
  const int third = (last - first + 1) / 3;
  std::vector<std::int16_t> top;
  std::vector<std::int16_t> bottom;
  for (int y = first; y <= last; ++y) {
    std::vector<std::int16_t>* into = y < first + third ? &top : (y > last - third ? &bottom : nullptr);
    if (!into) continue;
    for (int x = 0; x < d.width; ++x) {
      if (d(x, y) != kInvalidDisparity && d(x, y) > 0) into->push_back(d(x, y));
    }
  }
  if (top.size() < kMinPixelsPerThird || bottom.size() < kMinPixelsPerThird) return 0.0;
  return median(bottom) / median(top);
}

SparseLidarCheck checkSparseDisparity(const std::string& path, ImageView<const std::int16_t> d, int imageWidth) {
  SparseLidarCheck check;
  int largest = 0;
  for (int y = 0; y < d.height; ++y) {
    for (int x = 0; x < d.width; ++x) {
      if (d(x, y) != kInvalidDisparity) largest = std::max<int>(largest, d(x, y));
    }
  }
  if (largest / kDisparityScale >= imageWidth) {
    check.error = "the LiDAR disparities of '" + path + "' reach " + fixed(largest / double(kDisparityScale)) +
                  " px, more than the image's width (" + std::to_string(imageWidth) +
                  " px): is it a depth map? (-lidar_depth FILE -fb F reads KITTI depth PNGs)";
  }
  if (namedKind(path) == NamedKind::Depth) {
    check.warnings.push_back("'" + path + "' is named like a depth map, but -lidar reads disparities (KITTI "
                             "disparity PNG); for depths give -lidar_depth FILE -fb F");
  }
  const double trend = rowTrend(d);
  if (trend > 0.0 && trend < kDepthLikeTrend) {
    check.warnings.push_back("the values of '" + path + "' shrink toward the bottom of the image (bottom/top median " +
                             fixed(trend) + "), as depths do; disparities grow there (the ground is near). If it "
                             "is a depth map, give -lidar_depth FILE -fb F");
  }
  return check;
}

SparseLidarCheck checkSparseDepth(const std::string& path, ImageView<const std::int16_t> d) {
  SparseLidarCheck check;
  if (namedKind(path) == NamedKind::Disparity) {
    check.warnings.push_back("'" + path + "' is named like a disparity map, but -lidar_depth reads depths (KITTI "
                             "depth PNG, metres*256); for disparities give -lidar FILE");
  }
  const double trend = rowTrend(d);
  if (trend > 0.0 && trend < kDepthLikeTrend) {
    check.warnings.push_back("the depths of '" + path + "' grow toward the bottom of the image (their disparities' "
                             "bottom/top median " + fixed(trend) + "), as disparities do; depths shrink there "
                             "(the ground is near). If it is a disparity map, give -lidar FILE");
  }
  return check;
}

}  // namespace io
}  // namespace lidar_sgm
