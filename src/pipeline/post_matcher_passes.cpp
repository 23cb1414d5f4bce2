#include "pipeline/post_matcher_passes.hpp"

#include <algorithm>

#include "lidar_sgm/pipeline/min_confidence.hpp"
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
#include "pipeline/fast/fast_passes.hpp"
#endif

namespace lidar_sgm {

#ifndef LIDAR_SGM_HAVE_FAST_PASSES
namespace fast {
struct FastPassBuffers {};
}  // namespace fast
#endif

PostMatcherPasses::PostMatcherPasses() : buffers_(new fast::FastPassBuffers) {}
PostMatcherPasses::~PostMatcherPasses() = default;

bool PostMatcherPasses::fastBuilt() {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  return true;
#else
  return false;
#endif
}

void PostMatcherPasses::select(Backend backend, int threads) {
  fast_ = fastBuilt() && backend != Backend::CpuRef;
  threads_ = std::max(1, threads);
}

void PostMatcherPasses::project(const std::vector<Eigen::Vector3f>& pointsLidar,
                                const geometry::StereoCalibration& calibration,
                                const geometry::ProjectionOptions& options, geometry::ProjectedLidar& out) {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) {
    fast::project(pointsLidar, calibration, options, out, *buffers_, threads_);
    return;
  }
#endif
  out = geometry::project(pointsLidar, calibration, options);
}

PairOrientation PostMatcherPasses::pairOrientationFromLidar(const GrayImageView& left, const GrayImageView& right,
                                                           const std::vector<LidarSample>& lidar) {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) return fast::pairOrientationFromLidar(left, right, lidar, *buffers_, threads_);
#endif
  return lidar_sgm::pairOrientationFromLidar(left, right, lidar);
}

PairOrientation PostMatcherPasses::pairOrientationFromStereo(const GrayImageView& left, const GrayImageView& right,
                                                            int minDisparity, int numDisparities) {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) return fast::pairOrientationFromStereo(left, right, minDisparity, numDisparities, *buffers_, threads_);
#endif
  return lidar_sgm::pairOrientationFromStereo(left, right, minDisparity, numDisparities);
}

OutputFilterStats PostMatcherPasses::applyOutputFilters(ImageView<std::int16_t> disparity16,
                                                        const std::vector<LidarSample>& samples,
                                                        const GrayImageView& left, const OutputFilterOptions& options) {
  OutputFilterStats stats;
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) {
    stats.sky = fast::removeSky(disparity16, samples, left, options.sky, *buffers_, threads_);
    stats.outliers = fast::removeOutliers(disparity16, options.outliers, *buffers_, threads_);
    return stats;
  }
#endif
  stats.sky = removeSky(disparity16, samples, left, options.sky);
  stats.outliers = removeOutliers(disparity16, options.outliers);
  return stats;
}

void PostMatcherPasses::confidenceOfValidPixels(ImageView<std::int16_t> disparity,
                                                ImageView<const std::uint8_t> matched, double minConfidence,
                                                Image<std::uint8_t>& confidence) {
  if (matched.empty()) {
    confidence = Image<std::uint8_t>();
    return;
  }
  confidence.resize(disparity.width, disparity.height);
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) {
    fast::confidenceOfValidPixels(disparity, matched, confidence.view(), std::max(minConfidence, 0.0), threads_);
    return;
  }
#endif
  // The matcher's confidence, 0 where a later step (the crop, the filters) removed the disparity.
  for (int y = 0; y < disparity.height; ++y) {
    for (int x = 0; x < disparity.width; ++x) {
      confidence(x, y) = disparity(x, y) == kInvalidDisparity ? 0 : matched(x, y);
    }
  }
  if (minConfidence > 0.0) applyMinConfidence(disparity, confidence.view(), minConfidence);
}

std::size_t PostMatcherPasses::anchorToLidar(ImageView<std::int16_t> disparity16,
                                             const std::vector<LidarSample>& samples,
                                             const LidarAnchorOptions& options, LidarAnchorBuffers& buffers) {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) return fast::anchorToLidar(disparity16, samples, options, buffers, *buffers_, threads_);
#endif
  return lidar_sgm::anchorToLidar(disparity16, samples, options, buffers);
}

void PostMatcherPasses::reproject(ImageView<const std::int16_t> disparity16,
                                  const geometry::StereoCalibration& calibration,
                                  const geometry::ReprojectionOptions& options, Image<float>& depth,
                                  geometry::DenseCloud& cloud) {
#ifdef LIDAR_SGM_HAVE_FAST_PASSES
  if (fast_) {
    fast::depthImage(disparity16, calibration.focalBaseline(), options.maxDepth, depth, *buffers_, threads_);
    fast::reproject(disparity16, calibration, options, cloud, *buffers_, threads_);
    return;
  }
#endif
  geometry::depthImage(disparity16, calibration.focalBaseline(), options.maxDepth, depth);
  cloud = geometry::reproject(disparity16, calibration, options);
}

}  // namespace lidar_sgm
