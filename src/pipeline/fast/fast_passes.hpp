#pragma once
// The passes after the matcher, fast: vectorised where the arithmetic allows (Highway, the
// instruction set chosen at run time) and split among threads by fixed row ranges. Each function
// has the name and the result of its specification, bit for bit and for any thread count:
// geometry::project (projection.cpp), pairOrientationFromLidar and pairOrientationFromStereo
// (pair_orientation.cpp), removeSky (sky_mask.cpp), removeOutliers (outlier_filter.cpp), the Densifier's confidence of the
// valid pixels and applyMinConfidence (min_confidence.cpp), anchorToLidar (lidar_anchor.cpp),
// geometry::depthImage and geometry::reproject (reprojection.cpp). Their buffers live in
// FastPassBuffers, kept between frames: after the first frame of a size nothing is allocated.
// Compiled with the fast cpu backend (Highway).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "geometry/projection_steps.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"
#include "lidar_sgm/pipeline/outlier_filter.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"
#include "lidar_sgm/pipeline/sky_mask.hpp"
#include "pipeline/fast/depth_table.hpp"
#include "pipeline/lidar_anchor_rows.hpp"
#include "pipeline/pair_orientation_votes.hpp"

namespace lidar_sgm {
namespace fast {

/// project's buffers: per range of the points, their candidates, counts and kept samples; the
/// nearest point per pixel and the rows any point projects into.
struct ProjectionRanges {
  std::vector<std::vector<geometry::ProjectionCandidate>> candidates;
  std::vector<geometry::ProjectionStats> stats;
  std::vector<std::vector<LidarSample>> samples;
  std::vector<std::vector<std::size_t>> sourceIndex;
  std::vector<std::size_t> occluded;
  Image<std::int16_t> nearest;
  std::vector<std::uint8_t> occupied;
};

/// Grows only: a frame of the size seen before reuses every buffer.
struct FastPassBuffers {
  // project: the ranges' candidates and samples, the nearest image.
  ProjectionRanges projection;
  // pairOrientationFromLidar and ...FromStereo: each range's votes; the stereo grid's rows.
  std::vector<PairOrientation> pairVotes;
  std::vector<StereoGridScratch> stereoGridScratch;
  // removeOutliers: the input disparity with `radius` invalid columns on each side.
  std::vector<std::int16_t> paddedDisparity;
  // removeSky: per column, and per pixel of the rows that hold candidates.
  std::vector<int> columnTop, columnMin, candidateEnd, farLimit;
  std::vector<std::uint8_t> levels;      // the left image in 8-bit levels
  std::vector<std::uint16_t> gradient;   // |dx| + |dy| of the levels
  std::vector<std::int32_t> columnSums;  // per range: the window's column sums of the gradient
  std::vector<std::int64_t> prefix;      // per range: running sums along a row
  std::vector<std::uint8_t> skyLike, sky, nearSkyRow, nearAny;
  std::vector<std::size_t> stack;
  // depthImage and reproject: z of each x16 disparity; reproject: the points of each sampled row.
  DepthTable depthTable;
  std::vector<int> rowPoints;
  std::vector<std::size_t> removedPerRange;
  // anchorToLidar: the frame's plan (its weights) and the pixels each range moved.
  AnchorPlan anchorPlan;
  std::vector<std::size_t> anchoredPerRange;
};

/// geometry::project's result and checks, written into `out` (whose vectors keep their capacity
/// between frames).
void project(const std::vector<Eigen::Vector3f>& pointsLidar, const geometry::StereoCalibration& calibration,
             const geometry::ProjectionOptions& options, geometry::ProjectedLidar& out, FastPassBuffers& buffers,
             int threads);

/// pairOrientationFromLidar's votes (pair_orientation.hpp).
PairOrientation pairOrientationFromLidar(const GrayImageView& left, const GrayImageView& right,
                                         const std::vector<LidarSample>& lidar, FastPassBuffers& buffers,
                                         int threads);

/// pairOrientationFromStereo's votes (pair_orientation.hpp).
PairOrientation pairOrientationFromStereo(const GrayImageView& left, const GrayImageView& right, int minDisparity,
                                          int numDisparities, FastPassBuffers& buffers, int threads);

/// removeSky's result (sky_mask.hpp), also the option checks and their messages.
std::size_t removeSky(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                      const GrayImageView& left, const SkyFilterOptions& options, FastPassBuffers& buffers,
                      int threads);

/// removeOutliers' result (outlier_filter.hpp), also the option checks and their messages.
std::size_t removeOutliers(ImageView<std::int16_t> disparity16, const OutlierFilterOptions& options,
                           FastPassBuffers& buffers, int threads);

/// confidence = matched where disparity is valid, else 0; then applyMinConfidence(disparity,
/// confidence, minConfidence) (min_confidence.hpp), with its checks. Same sizes required.
void confidenceOfValidPixels(ImageView<std::int16_t> disparity, ImageView<const std::uint8_t> matched,
                             ImageView<std::uint8_t> confidence, double minConfidence, int threads);

/// anchorToLidar's result and checks (lidar_anchor.hpp); `sums` are the caller's, as there.
std::size_t anchorToLidar(ImageView<std::int16_t> disparity16, const std::vector<LidarSample>& samples,
                          const LidarAnchorOptions& options, LidarAnchorBuffers& sums, FastPassBuffers& buffers,
                          int threads);

/// geometry::depthImage's result and checks; `depth` is resized (kept when the size is the same).
void depthImage(ImageView<const std::int16_t> disparity16, double focalBaseline, double maxDepth, Image<float>& depth,
                FastPassBuffers& buffers, int threads);

/// geometry::reproject's result and checks, written into `cloud` (whose vectors keep their
/// capacity between frames).
void reproject(ImageView<const std::int16_t> disparity16, const geometry::StereoCalibration& calibration,
               const geometry::ReprojectionOptions& options, geometry::DenseCloud& cloud, FastPassBuffers& buffers,
               int threads);

}  // namespace fast
}  // namespace lidar_sgm
