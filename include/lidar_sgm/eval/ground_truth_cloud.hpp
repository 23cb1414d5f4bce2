#pragma once
/// @file ground_truth_cloud.hpp  A frame's methods scored in 3D against the frame's ground truth
/// as a cloud (the KITTI142 protocol): the GT disparity and each method's disparity reprojected
/// as the tools reproject them (geometry::reproject: the rectified left camera's frame, up to the
/// tools' 80 m), then cloud_distance.hpp's precision, completeness and F-score per range band.

#include <cstdint>
#include <optional>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/eval/cloud_distance.hpp"
#include "lidar_sgm/eval/eval_frame.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace eval {

/// [m] The tau the tables show (docs/EVALUATION.md says why): the JSON has every tau of
/// groundTruthCloudOptions().
constexpr double kGroundTruthCloudTau = 0.2;

/// The protocol's scoring: taus 0.1, 0.2 and 0.5 m, range bands 0-10-20-40-80 m from the left
/// camera, one thread (the frames run in parallel).
CloudDistanceOptions groundTruthCloudOptions();

/// The reprojection of both clouds: the tools' (ReprojectionOptions' defaults) in the camera frame.
geometry::ReprojectionOptions groundTruthCloudReprojection();

/// A frame's GT as a reference cloud, its kd-tree built once for all the frame's methods.
class GroundTruthCloud {
 public:
  /// Throws std::invalid_argument when the frame has no calibration or no GT point.
  explicit GroundTruthCloud(const EvalFrame& frame);

  /// `disparity` (x16, kInvalidDisparity = none; the frame's size) reprojected and held against
  /// the GT cloud. Precision is over the points of the pixels that have GT: elsewhere KITTI did
  /// not measure, so a point there cannot be judged (as the disparity metrics); every point
  /// serves completeness. std::nullopt when the disparity gives no point at all.
  std::optional<CloudDistanceScore> score(ImageView<const std::int16_t> disparity) const;

  std::size_t size() const { return reference_.size(); }

 private:
  const EvalFrame& frame_;
  ReferenceCloud reference_;
};

}  // namespace eval
}  // namespace lidar_sgm
