#pragma once
/// @file cloud_preview.hpp  A picture of a dense cloud seen from above and behind the rig: a
/// small off-screen renderer (z-buffered square splats, OpenCV drawing) for docs and the tools.
/// Chosen so that what a picture from the rig camera hides stands out: a curtain of points in
/// the sky (15-20 m high, 20-80 m ahead) stands up above the ground, and flying points hang
/// over the dark background.

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace io {

/// The virtual pinhole camera and what is drawn. Rig frame = the rectified left camera (x
/// right, y down, z forward); the virtual camera sits at (0, -cameraHeight, -cameraBehind),
/// looks along +z pitched down by pitchDeg, no roll.
struct CloudPreviewOptions {
  int width = 960;                ///< picture size [px]
  int height = 600;
  double cameraHeight = 18.0;     ///< virtual camera above the rig camera [m]
  double cameraBehind = 25.0;     ///< virtual camera behind the rig camera [m]
  double pitchDeg = 19.0;         ///< looking down by this angle [deg], in (-90, 90)
  double fieldOfViewDeg = 70.0;   ///< horizontal field of view [deg], in (0, 180)
  /// Points farther ahead than this (rig camera z [m]) are not drawn; also the range of the
  /// depth color map and the grid's extent.
  double maxDepth = 80.0;
  /// Splat edge at the point [m]: on screen pointSize * f / z' px (z' = depth in the virtual
  /// camera), rounded, clamped to [1, maxSplatPx]: near points are big, far ones small.
  double pointSize = 0.12;
  int maxSplatPx = 8;
  /// The ground lies this far below the rig camera [m] (KITTI's camera: 1.65 m): where the
  /// grid and the rig marker are drawn.
  double groundBelowCamera = 1.65;
  bool grid = true;     ///< faint ground grid every 10 m, distances labelled every 20 m
  bool markRig = true;  ///< a triangle on the ground at the rig, pointing forward
};

/// Checks the options; throws std::invalid_argument naming the first bad one.
void validate(const CloudPreviewOptions& options);

/// Renders `pointsCamera` (rig camera frame [m]; non-finite points are skipped) in their
/// `colors` (one per point), or, with `colors` empty, in a turbo color map of the rig depth z
/// (blue near ... red at maxDepth). Dark background; nearest splat wins (ties: the earlier
/// point), single-threaded: the same cloud gives the same bytes. Returns 8-bit BGR.
/// Throws std::invalid_argument for an empty cloud, a color count other than the point
/// count, or bad options.
cv::Mat renderCloudPreview(const std::vector<Eigen::Vector3f>& pointsCamera, const std::vector<Rgb8>& colors,
                           const CloudPreviewOptions& options = {});

/// The pixel (column, row, as doubles: floor() gives the pixel) where a rig-frame point lands
/// in the preview, and its depth in the virtual camera (<= 0: behind it). For tests and for
/// drawing on a preview.
Eigen::Vector3d projectToPreview(const Eigen::Vector3d& pointCamera, const CloudPreviewOptions& options);

/// The points of a dense cloud in the rig camera frame (T_cam_lidar applied when `frame` is
/// Lidar), with the colors of their pixels in `color` (empty view: no colors).
void previewInputs(const geometry::DenseCloud& cloud, geometry::OutputFrame frame,
                   const geometry::StereoCalibration& calibration, ImageView<const Rgb8> color,
                   std::vector<Eigen::Vector3f>& pointsCamera, std::vector<Rgb8>& colors);

}  // namespace io
}  // namespace lidar_sgm
