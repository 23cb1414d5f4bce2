#pragma once
// The Densifier's passes around the matcher (the scan's projection before it; output filters, the
// LiDAR anchor, confidence, minimum confidence, depth and cloud after it), each run as its
// specification's loops (geometry/projection.cpp, sky_mask.cpp, outlier_filter.cpp,
// lidar_anchor.cpp, min_confidence.cpp, geometry/reprojection.cpp) or as the
// fast passes (fast/fast_passes.hpp), which give the same bytes. Which: the fast ones with every backend but cpu_ref, where they are
// built (with the fast cpu backend); cpu_ref runs the specification end to end.

#include <cstdint>
#include <memory>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"
#include "lidar_sgm/pipeline/output_filters.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"

namespace lidar_sgm {

namespace fast {
struct FastPassBuffers;
}  // namespace fast

class PostMatcherPasses {
 public:
  PostMatcherPasses();
  ~PostMatcherPasses();
  PostMatcherPasses(const PostMatcherPasses&) = delete;
  PostMatcherPasses& operator=(const PostMatcherPasses&) = delete;

  /// Whether the fast passes are built into this library.
  static bool fastBuilt();
  /// The passes of the next frame: fast for `backend` (resolved) unless it is cpu_ref or they are
  /// not built, on `threads` threads (>= 1; the result never depends on it).
  void select(Backend backend, int threads);
  bool fast() const { return fast_; }

  /// geometry::project into `out` (whose vectors keep their capacity on the fast path).
  void project(const std::vector<Eigen::Vector3f>& pointsLidar, const geometry::StereoCalibration& calibration,
               const geometry::ProjectionOptions& options, geometry::ProjectedLidar& out);
  /// pairOrientationFromLidar and pairOrientationFromStereo (pair_orientation.hpp).
  PairOrientation pairOrientationFromLidar(const GrayImageView& left, const GrayImageView& right,
                                           const std::vector<LidarSample>& lidar);
  PairOrientation pairOrientationFromStereo(const GrayImageView& left, const GrayImageView& right, int minDisparity,
                                            int numDisparities);
  /// Sky first (it removes whole runs from the top of a column), then the isolated points, some
  /// of which the sky removal leaves behind at the border of the removed region.
  OutputFilterStats applyOutputFilters(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                                       const GrayImageView& left, const OutputFilterOptions& options);
  /// confidence = matched where the disparity is valid, else 0 (resized to the disparity's size,
  /// kept when it is the same; empty when `matched` is); then, for minConfidence > 0, the
  /// pixels below it lose both (applyMinConfidence).
  void confidenceOfValidPixels(ImageView<std::int16_t> disparity, ImageView<const std::uint8_t> matched,
                               double minConfidence, Image<std::uint8_t>& confidence);
  /// anchorToLidar (lidar_anchor.hpp); `buffers` are kept between frames by the caller.
  std::size_t anchorToLidar(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                            const LidarAnchorOptions& options, LidarAnchorBuffers& buffers);
  /// geometry::depthImage and geometry::reproject; `cloud` keeps its capacity on the fast path.
  void reproject(ImageView<const std::int16_t> disparity16, const geometry::StereoCalibration& calibration,
                 const geometry::ReprojectionOptions& options, Image<float>& depth, geometry::DenseCloud& cloud);

 private:
  bool fast_ = false;
  int threads_ = 1;
  std::unique_ptr<fast::FastPassBuffers> buffers_;  ///< kept between frames
};

}  // namespace lidar_sgm
