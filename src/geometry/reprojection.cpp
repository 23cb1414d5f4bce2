#include "lidar_sgm/geometry/reprojection.hpp"

#include <limits>

#include "geometry/reprojection_checks.hpp"

namespace lidar_sgm {
namespace geometry {

namespace {

template <typename T>
void checkInputs(ImageView<const T> disparity, const StereoCalibration& calibration,
                 const ReprojectionOptions& options) {
  checkReprojectionInputs(disparity.width, disparity.height, calibration, options);
}

/// The cloud of a depth per pixel: `depthAt(x, y)` is z [m], 0 where the pixel has none.
template <typename DepthAt>
DenseCloud reprojectDepths(const StereoCalibration& calibration, const ReprojectionOptions& options,
                           DepthAt depthAt) {
  // One transform for the whole image: camera -> output frame.
  const Eigen::Isometry3d T_out_cam =
      options.frame == OutputFrame::Lidar ? calibration.T_lidar_cam() : Eigen::Isometry3d::Identity();
  const float nan = std::numeric_limits<float>::quiet_NaN();

  DenseCloud cloud;
  const int columns = (calibration.width + options.stride - 1) / options.stride;
  const int rows = (calibration.height + options.stride - 1) / options.stride;
  // At most one point per sampled pixel: reserved once, so that a dense frame's ~0.4 M points are
  // not copied over and over as the vectors grow.
  cloud.points.reserve(static_cast<std::size_t>(columns) * rows);
  cloud.pixels.reserve(cloud.points.capacity());
  for (int y = 0; y < calibration.height; y += options.stride) {
    for (int x = 0; x < calibration.width; x += options.stride) {
      const double z = depthAt(x, y);
      if (!(z > 0.0) || z > options.maxDepth) {
        if (options.keepOrganized) {
          cloud.points.emplace_back(nan, nan, nan);
          cloud.pixels.push_back({x, y});
          cloud.isDense = false;
        }
        continue;
      }
      const Eigen::Vector3d camera((x - calibration.cx()) * z / calibration.fx(),
                                   (y - calibration.cy()) * z / calibration.fy(), z);
      cloud.points.push_back((T_out_cam * camera).cast<float>());
      cloud.pixels.push_back({x, y});
    }
  }
  if (options.keepOrganized) {
    cloud.width = columns;
    cloud.height = rows;
  } else {
    cloud.width = static_cast<int>(cloud.points.size());
    cloud.height = 1;
  }
  return cloud;
}

}  // namespace

DenseCloud reproject(ImageView<const std::int16_t> disparity16, const StereoCalibration& calibration,
                     const ReprojectionOptions& options) {
  checkInputs(disparity16, calibration, options);
  const double fb = calibration.focalBaseline();
  return reprojectDepths(calibration, options, [&](int x, int y) {
    // Eq. 3 backwards: z = f*b/d; invalid and non-positive disparities give no point.
    const int d16 = disparity16(x, y);
    return d16 > 0 ? fb * kDisparityScale / d16 : 0.0;
  });
}

DenseCloud reproject(ImageView<const float> disparity, const StereoCalibration& calibration,
                     const ReprojectionOptions& options) {
  checkInputs(disparity, calibration, options);
  const double fb = calibration.focalBaseline();
  return reprojectDepths(calibration, options, [&](int x, int y) {
    const float d = disparity(x, y);  // NaN fails the test too
    return d > 0.0f ? fb / static_cast<double>(d) : 0.0;
  });
}

void depthImage(ImageView<const std::int16_t> disparity16, double focalBaseline, double maxDepth,
                Image<float>& depth) {
  checkDepthImageInputs(focalBaseline, maxDepth);
  depth.resize(disparity16.width, disparity16.height);
  for (int y = 0; y < disparity16.height; ++y) {
    const std::int16_t* in = disparity16.row(y);
    for (int x = 0; x < disparity16.width; ++x) {
      // The arithmetic of reproject(), so that depth(x, y) is the z of the point at (x, y).
      const int d16 = in[x];
      const double z = d16 > 0 ? focalBaseline * kDisparityScale / d16 : 0.0;
      depth(x, y) = z > 0.0 && z <= maxDepth ? static_cast<float>(z) : 0.0f;
    }
  }
}

}  // namespace geometry
}  // namespace lidar_sgm
