#pragma once
/// @file densify.hpp  LiDAR-SGM in an Open3D pipeline: an open3d::geometry::PointCloud scan
/// (and optionally the rectified pair as open3d::geometry::Image) in, the dense cloud out, colored
/// from the left image. A thin adapter over the Densifier, as SGMDensification is for PCL: the
/// same frame gives the same points as Densifier::run and the tools.
///
/// @code
/// #include <open3d/io/ImageIO.h>
/// #include <lidar_sgm/io/calibration_io.hpp>
/// #include <lidar_sgm/open3d/densify.hpp>
///
/// // One KITTI-layout frame, e.g. densify(scan, "data/sample", "000000"); scan: LiDAR frame [m].
/// std::shared_ptr<open3d::geometry::PointCloud> densify(const open3d::geometry::PointCloud& scan,
///                                                       const std::string& dir, const std::string& name) {
///   auto left = open3d::io::CreateImageFromFile(dir + "/image_2/" + name + ".png");   // gray/RGB, 8/16 bit
///   auto right = open3d::io::CreateImageFromFile(dir + "/image_3/" + name + ".png");  // nullptr -> LiDAR-only
///   lidar_sgm::Parameters parameters;              // the tools' defaults
///   parameters.alpha = 0.7f;                       // LiDAR weight (Eq. 5)
///   return lidar_sgm::densify(scan, lidar_sgm::io::readCalibration(dir + "/calib/" + name + ".txt"),
///                             left.get(), right.get(), parameters);  // colors_ in [0, 1] from the left image
/// }
/// @endcode
///
/// Modes as the Densifier's: left and right -> fused (Eq. 5); left only -> LiDAR-only SGM with
/// colors; neither -> LiDAR-only SGM, no colors. A right image without a left one is an error.
/// Errors (empty scan, image formats or sizes, calibration, parameters, no point in the image)
/// throw std::invalid_argument / std::runtime_error naming the problem.

#include <memory>

#include <open3d/geometry/Image.h>
#include <open3d/geometry/PointCloud.h>

#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/open3d/image_conversion.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {

/// One frame with the Densifier's defaults (those of the tools) but for `parameters`. The output
/// is in the LiDAR frame, unorganized (valid points only), colors_ in [0, 1] from `left` when it
/// is given (else no colors).
std::shared_ptr<::open3d::geometry::PointCloud> densify(const ::open3d::geometry::PointCloud& scan,
                                                        const geometry::StereoCalibration& calibration,
                                                        const ::open3d::geometry::Image* left = nullptr,
                                                        const ::open3d::geometry::Image* right = nullptr,
                                                        const Parameters& parameters = Parameters());

/// One frame with a Densifier the caller configured (calibration, every option; its buffers are
/// reused over a sequence), which keeps the frame's disparity(), depth(), confidence() and
/// timings(). Its images are replaced by `left` / `right` (null: none), so that a frame never
/// uses the previous one's. Organized output (ReprojectionOptions::keepOrganized) keeps NaN points.
std::shared_ptr<::open3d::geometry::PointCloud> densify(Densifier& densifier,
                                                        const ::open3d::geometry::PointCloud& scan,
                                                        const ::open3d::geometry::Image* left = nullptr,
                                                        const ::open3d::geometry::Image* right = nullptr);

/// The rectified pair as Open3D images (same size, same channels and bit depth), matched on their
/// gray levels (Open3dGray); the left one colors the output.
void setStereoPair(Densifier& densifier, const ::open3d::geometry::Image& left, const ::open3d::geometry::Image& right);

}  // namespace lidar_sgm
