// pairOrientationFromLidar and pairOrientationFromStereo (pair_orientation.cpp, the
// specification), fast: the LiDAR tests or the stereo grid's rows split among threads
// (pair_orientation_votes.hpp); each range's counts are added. The patch arithmetic is the
// specification's, compiled with the same flags.
#include <utility>

#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"
#include "pipeline/pair_orientation_votes.hpp"

namespace lidar_sgm {
namespace fast {
namespace {

/// The ranges' counts added into `votes`.
void addVotes(const std::vector<PairOrientation>& perRange, PairOrientation& votes) {
  for (const PairOrientation& range : perRange) {
    votes.tested += range.tested;
    votes.givenWins += range.givenWins;
    votes.swappedWins += range.swappedWins;
  }
}

}  // namespace

PairOrientation pairOrientationFromLidar(const GrayImageView& left, const GrayImageView& right,
                                         const std::vector<LidarSample>& lidar, FastPassBuffers& buffers,
                                         int threads) {
  PairOrientation votes;
  votes.fromLidar = true;
  if (!pairVotable(left, right)) return votes;
  const std::size_t tests = lidarTestCount(lidar.size());
  std::vector<PairOrientation>& perRange = buffers.pairVotes;
  const int count = static_cast<int>(tests);  // at most about 4000
  perRange.assign(static_cast<std::size_t>(rangeCount(count, threads)), PairOrientation());
  parallelRanges(count, threads, [&](int t, int begin, int end) {
    PairOrientation range;  // counted in a local: the ranges' counts lie side by side
    voteAtLidarSamples(left, right, lidar, static_cast<std::size_t>(begin), static_cast<std::size_t>(end), range);
    perRange[static_cast<std::size_t>(t)] = range;
  });
  addVotes(perRange, votes);
  return votes;
}

PairOrientation pairOrientationFromStereo(const GrayImageView& left, const GrayImageView& right, int minDisparity,
                                          int numDisparities, FastPassBuffers& buffers, int threads) {
  PairOrientation votes;
  if (!pairVotable(left, right)) return votes;
  const StereoGrid grid = stereoGrid(left, minDisparity, numDisparities);
  const int ranges = rangeCount(grid.rows, threads);
  std::vector<PairOrientation>& perRange = buffers.pairVotes;
  perRange.assign(static_cast<std::size_t>(ranges), PairOrientation());
  buffers.stereoGridScratch.resize(static_cast<std::size_t>(ranges));
  parallelRanges(grid.rows, threads, [&](int t, int begin, int end) {
    // In a local, moved in and out: the ranges' vectors lie side by side (no false sharing).
    StereoGridScratch scratch = std::move(buffers.stereoGridScratch[static_cast<std::size_t>(t)]);
    PairOrientation range;
    voteAtGridRows(left, right, grid, begin, end, range, scratch);
    perRange[static_cast<std::size_t>(t)] = range;
    buffers.stereoGridScratch[static_cast<std::size_t>(t)] = std::move(scratch);
  });
  addVotes(perRange, votes);
  return votes;
}

}  // namespace fast
}  // namespace lidar_sgm
