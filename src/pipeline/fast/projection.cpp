// geometry::project (projection.cpp, the specification), fast: its steps (projection_steps.hpp) on
// ranges split among threads, the candidates and the kept samples of each range concatenated in
// range order, so that the samples come out in the specification's order; the nearest image, the
// occupied rows and every range's vectors are kept between frames. No SIMD: the arithmetic is the
// specification's double precision, compiled with the same flags.
#include <algorithm>
#include <utility>

#include "geometry/projection_steps.hpp"
#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"

namespace lidar_sgm {
namespace fast {

void project(const std::vector<Eigen::Vector3f>& pointsLidar, const geometry::StereoCalibration& calibration,
             const geometry::ProjectionOptions& options, geometry::ProjectedLidar& out, FastPassBuffers& buffers,
             int threads) {
  const geometry::ProjectionPlan plan = geometry::planProjection(calibration, options);
  out.width = plan.width;
  out.height = plan.height;
  out.stats = geometry::ProjectionStats();
  out.stats.input = pointsLidar.size();
  out.samples.clear();
  out.sourceIndex.clear();

  // The points' ranges: their candidates, and the counts of the points dropped before the filter.
  const int pointRanges = rangeCount(static_cast<int>(std::min<std::size_t>(pointsLidar.size(), 1u << 30)), threads);
  ProjectionRanges& ranges = buffers.projection;
  ranges.candidates.resize(static_cast<std::size_t>(pointRanges));
  ranges.stats.assign(static_cast<std::size_t>(pointRanges), geometry::ProjectionStats());
  ranges.samples.resize(static_cast<std::size_t>(pointRanges));
  ranges.sourceIndex.resize(static_cast<std::size_t>(pointRanges));
  ranges.occluded.assign(static_cast<std::size_t>(pointRanges), 0);
  const std::size_t n = pointsLidar.size();
  parallelRanges(pointRanges, threads, [&](int t, int, int) {
    const std::size_t begin = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(pointRanges);
    const std::size_t end = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(pointRanges);
    // Worked on in locals, moved in and out: the ranges' vectors and counts lie side by side, and
    // a thread growing its own would write to the cache line of its neighbour's (false sharing).
    std::vector<geometry::ProjectionCandidate> candidates = std::move(ranges.candidates[static_cast<std::size_t>(t)]);
    candidates.clear();
    geometry::ProjectionStats stats;
    geometry::projectCandidates(plan, pointsLidar, begin, end, candidates, stats);
    ranges.candidates[static_cast<std::size_t>(t)] = std::move(candidates);
    ranges.stats[static_cast<std::size_t>(t)] = stats;
  });
  std::size_t candidateCount = 0;
  for (int t = 0; t < pointRanges; ++t) {
    const geometry::ProjectionStats& s = ranges.stats[static_cast<std::size_t>(t)];
    out.stats.nonFinite += s.nonFinite;
    out.stats.behindCamera += s.behindCamera;
    out.stats.outOfRange += s.outOfRange;
    out.stats.outsideImage += s.outsideImage;
    candidateCount += ranges.candidates[static_cast<std::size_t>(t)].size();
  }

  const geometry::OcclusionFilter& filter = options.occlusion;
  if (filter.enabled && candidateCount > 0) {
    Image<std::int16_t>& nearest = ranges.nearest;
    nearest.resize(plan.width, plan.height);
    const ImageView<std::int16_t> nearestView = nearest.view();
    parallelRanges(plan.height, threads, [&](int, int y0, int y1) {
      std::fill(nearestView.row(y0), nearestView.row(y0) + static_cast<std::size_t>(y1 - y0) * plan.width,
                static_cast<std::int16_t>(kInvalidDisparity));
    });
    // A maximum per pixel: the order of the candidates does not matter (one thread; they are few).
    for (const auto& candidates : ranges.candidates) geometry::markNearest(candidates, nearestView);
    ranges.occupied.resize(static_cast<std::size_t>(plan.height));
    parallelRanges(plan.height, threads, [&](int, int y0, int y1) {
      geometry::occupiedRows(nearestView, y0, y1, ranges.occupied.data());
    });
    // The filter on equal shares of all candidates, the point ranges' lists taken as one in range
    // order: the camera sees a part of the scan, so the point ranges hold unequal numbers of
    // candidates (a KITTI scan: the first range most of them). Each share's kept samples come out in
    // the same order, so their concatenation in share order is the specification's.
    parallelRanges(pointRanges, threads, [&](int t, int, int) {
      const std::size_t i = static_cast<std::size_t>(t);
      const std::size_t shareBegin = candidateCount * i / static_cast<std::size_t>(pointRanges);
      const std::size_t shareEnd = candidateCount * (i + 1) / static_cast<std::size_t>(pointRanges);
      std::vector<LidarSample> samples = std::move(ranges.samples[i]);  // in locals, as above
      std::vector<std::size_t> sourceIndex = std::move(ranges.sourceIndex[i]);
      samples.clear();
      sourceIndex.clear();
      std::size_t occluded = 0;
      std::size_t offset = 0;  // the index among all candidates of this range's first
      for (const std::vector<geometry::ProjectionCandidate>& candidates : ranges.candidates) {
        const std::size_t begin = std::max(shareBegin, offset);
        const std::size_t end = std::min(shareEnd, offset + candidates.size());
        if (begin < end) {
          occluded += geometry::keepUnoccluded(candidates, begin - offset, end - offset, nearestView,
                                               ranges.occupied.data(), filter, samples, sourceIndex);
        }
        offset += candidates.size();
      }
      ranges.occluded[i] = occluded;
      ranges.samples[i] = std::move(samples);
      ranges.sourceIndex[i] = std::move(sourceIndex);
    });
    out.samples.reserve(candidateCount);
    out.sourceIndex.reserve(candidateCount);
    for (int t = 0; t < pointRanges; ++t) {
      const std::size_t i = static_cast<std::size_t>(t);
      out.stats.occluded += ranges.occluded[i];
      out.samples.insert(out.samples.end(), ranges.samples[i].begin(), ranges.samples[i].end());
      out.sourceIndex.insert(out.sourceIndex.end(), ranges.sourceIndex[i].begin(), ranges.sourceIndex[i].end());
    }
  } else {
    out.samples.reserve(candidateCount);
    out.sourceIndex.reserve(candidateCount);
    for (const auto& candidates : ranges.candidates) geometry::keepAll(candidates, out.samples, out.sourceIndex);
  }
  out.stats.kept = out.samples.size();
}

}  // namespace fast
}  // namespace lidar_sgm
