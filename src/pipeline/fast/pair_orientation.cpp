// pairOrientationFromLidar (pair_orientation.cpp, the specification), fast: its tests split among
// threads (pair_orientation_votes.hpp); each range's counts are added. The patch arithmetic is
// the specification's (double precision), compiled with the same flags.
#include "pipeline/fast/fast_passes.hpp"
#include "pipeline/fast/parallel.hpp"
#include "pipeline/pair_orientation_votes.hpp"

namespace lidar_sgm {
namespace fast {

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
    voteAtLidarSamples(left, right, lidar, static_cast<std::size_t>(begin), static_cast<std::size_t>(end),
                       perRange[static_cast<std::size_t>(t)]);
  });
  for (const PairOrientation& range : perRange) {
    votes.tested += range.tested;
    votes.givenWins += range.givenWins;
    votes.swappedWins += range.swappedWins;
  }
  return votes;
}

}  // namespace fast
}  // namespace lidar_sgm
