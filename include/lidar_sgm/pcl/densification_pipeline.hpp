#pragma once
/// @file densification_pipeline.hpp  The point-type-free work behind SGMDensification:
/// project the scan, run LiDAR-SGM, reproject the disparity. No PCL, no OpenCV.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/geometry/scan_extent.hpp"

namespace lidar_sgm {

/// 8-bit color of one pixel.
struct Rgb8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

/// Wall-clock time of the steps of the last run, in milliseconds.
struct DensificationTimings {
  double project = 0;    ///< cloud -> sparse LiDAR disparities (with the occlusion filter)
  double match = 0;      ///< LiDAR-SGM (all stages of the core)
  double reproject = 0;  ///< dense disparity -> 3D points (and color)
  double total() const { return project + match + reproject; }
};

/// Holds the calibration, images, parameters and buffers between frames; run() does one frame.
/// Errors are std::invalid_argument / std::runtime_error with a message naming the problem.
class DensificationPipeline {
 public:
  DensificationPipeline();

  void setCalibration(const geometry::StereoCalibration& calibration) { calibration_ = calibration; }
  const geometry::StereoCalibration& calibration() const { return calibration_; }

  /// 8-bit gray rectified pair (copied). Empty views clear the pair (LiDAR-only mode).
  void setStereoPair(ImageView<const std::uint8_t> left, ImageView<const std::uint8_t> right);
  /// 16-bit gray rectified pair (copied): census compares intensities, so nothing is lost to 8 bits.
  void setStereoPair(ImageView<const std::uint16_t> left, ImageView<const std::uint16_t> right);
  bool hasStereoPair() const { return !left_.empty() || !left16_.empty(); }
  /// Color for the output points (copied); empty clears it.
  void setColorImage(ImageView<const Rgb8> color);
  bool hasColorImage() const { return !color_.empty(); }

  void setParameters(const Parameters& params) { params_ = params; }
  const Parameters& parameters() const { return params_; }
  Parameters& parameters() { return params_; }
  void setBackend(Backend backend) { backend_ = backend; }
  Backend backend() const { return backend_; }
  void setProjectionOptions(const geometry::ProjectionOptions& o) { projectionOptions_ = o; }
  const geometry::ProjectionOptions& projectionOptions() const { return projectionOptions_; }
  geometry::ProjectionOptions& projectionOptions() { return projectionOptions_; }
  void setReprojectionOptions(const geometry::ReprojectionOptions& o) { reprojectionOptions_ = o; }
  const geometry::ReprojectionOptions& reprojectionOptions() const { return reprojectionOptions_; }
  geometry::ReprojectionOptions& reprojectionOptions() { return reprojectionOptions_; }

  /// LiDAR-only mode: clear the pixels above the scan's top and below its bottom point per
  /// column (+- lidarCoverageRows rows, +-2 columns), where nothing was measured (default on).
  void setCropToScan(bool crop) { cropToScan_ = crop; }
  bool cropToScan() const { return cropToScan_; }

  /// One frame: `pointsLidar` in the LiDAR frame. The image size is the calibration's, or the
  /// images' when the calibration has none (KITTI object files carry no size). Throws when
  /// the calibration, parameters or image sizes are invalid, or no point projects into the image.
  geometry::DenseCloud run(const std::vector<Eigen::Vector3f>& pointsLidar);

  /// The calibration the last run used (its size completed from the images).
  const geometry::StereoCalibration& usedCalibration() const { return used_; }
  const Image<std::int16_t>& disparity() const { return disparity_; }
  const geometry::ProjectedLidar& projected() const { return projected_; }
  const DensificationTimings& timings() const { return timings_; }
  MatchMode lastMode() const { return lastMode_; }
  /// The color of pixel (x, y): from the color image, else from the left image (gray); false
  /// when there is neither.
  bool colorAt(int x, int y, Rgb8& out) const;

 private:
  geometry::StereoCalibration resolveCalibration() const;

  geometry::StereoCalibration calibration_;
  geometry::StereoCalibration used_;
  Parameters params_;
  Backend backend_ = Backend::Auto;
  geometry::ProjectionOptions projectionOptions_;
  geometry::ReprojectionOptions reprojectionOptions_;
  Image<std::uint8_t> left_;
  Image<std::uint8_t> right_;
  Image<std::uint16_t> left16_;
  Image<std::uint16_t> right16_;
  Image<Rgb8> color_;
  std::unique_ptr<Matcher> matcher_;
  Backend matcherBackend_ = Backend::Auto;  ///< the backend matcher_ was created for
  Image<std::int16_t> disparity_;
  geometry::ProjectedLidar projected_;
  DensificationTimings timings_;
  MatchMode lastMode_ = MatchMode::LidarOnly;
  bool cropToScan_ = true;
};

}  // namespace lidar_sgm
