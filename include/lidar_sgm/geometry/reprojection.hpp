#pragma once
/// @file reprojection.hpp  A dense disparity image back into 3D: z = f*b/d (Eq. 3),
/// x = (u - cx) z / fx, y = (v - cy) z / fy, then into the LiDAR frame by default.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/core/huge_page_allocator.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/geometry/calibration.hpp"

namespace lidar_sgm {
namespace geometry {

enum class OutputFrame {
  Lidar,   ///< p_lidar = T_lidar_cam * p_cam: the input cloud's frame (the default)
  Camera,  ///< the rectified left camera (x right, y down, z forward)
};

struct ReprojectionOptions {
  OutputFrame frame = OutputFrame::Lidar;
  /// Pixels whose depth exceeds this [m] are dropped: at 80 m the KITTI disparity is 4.8 px
  /// and one x16 step is 0.5 m of depth. Infinity keeps every valid pixel.
  double maxDepth = 80.0;
  /// Every `stride`-th pixel in x and y (1 = all).
  int stride = 1;
  /// Organized: one point per sampled pixel, NaN where there is none (width x height, PCL's
  /// is_dense = false). Unorganized: valid points only, in row-major pixel order.
  bool keepOrganized = false;
};

/// The pixel a reprojected point came from (for color and for tracing back).
struct PixelIndex {
  int x = 0;
  int y = 0;
};

struct DenseCloud {
  int width = 0;   ///< organized: sampled columns; unorganized: number of points
  int height = 0;  ///< organized: sampled rows; unorganized: 1
  HugePageVector<Eigen::Vector3f> points;  ///< NaN coordinates for pixels without a point
  HugePageVector<PixelIndex> pixels;       ///< same order as points, also for NaN points
  bool isDense = true;                  ///< false when a point is NaN
  std::size_t size() const { return points.size(); }
};

/// `disparity16` is x16 fixed point with kInvalidDisparity (the matcher's output). Throws
/// std::invalid_argument for an invalid calibration, a disparity image of another size than
/// the calibration's, or stride < 1 / maxDepth <= 0.
DenseCloud reproject(ImageView<const std::int16_t> disparity16, const StereoCalibration& calibration,
                     const ReprojectionOptions& options = {});
/// The same for a disparity in pixels as float (a ground truth read from KITTI's 1/256 px files,
/// without rounding it to x16): z = f*b/d; <= 0 or NaN gives no point.
DenseCloud reproject(ImageView<const float> disparity, const StereoCalibration& calibration,
                     const ReprojectionOptions& options = {});

/// The dense depth image of `disparity16` (x16, kInvalidDisparity): z = f*b/d [m] (Eq. 3) per
/// pixel, the same z as reproject()'s points; 0 where there is no positive disparity or z
/// exceeds `maxDepth` (KITTI depth completion's "0 = none"). `depth` is resized to match.
/// Throws std::invalid_argument when focalBaseline or maxDepth is not positive.
void depthImage(ImageView<const std::int16_t> disparity16, double focalBaseline, double maxDepth,
                Image<float>& depth);

}  // namespace geometry
}  // namespace lidar_sgm
