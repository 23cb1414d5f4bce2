#pragma once
// pairOrientationFromLidar (pair_orientation.hpp) in its steps, for a caller that splits the tested
// samples among threads (fast/pair_orientation.cpp): the samples tested are every step-th, test t
// the sample t * step; votes on test ranges are counts, so their sum is the same for any split.

#include <cstddef>
#include <vector>

#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"

namespace lidar_sgm {

/// The sample step and the number of tests for `samples` samples (at most about 4000 tests).
std::size_t lidarTestStep(std::size_t samples);
std::size_t lidarTestCount(std::size_t samples);

/// Whether the pair can be voted on at all (two images of one size and depth).
bool pairVotable(const GrayImageView& left, const GrayImageView& right);

/// The votes of tests [begin, end) added to `votes` (tested, givenWins, swappedWins).
void voteAtLidarSamples(const GrayImageView& left, const GrayImageView& right, const std::vector<LidarSample>& lidar,
                        std::size_t begin, std::size_t end, PairOrientation& votes);

}  // namespace lidar_sgm
