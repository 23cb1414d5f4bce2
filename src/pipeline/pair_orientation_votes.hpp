#pragma once
// pairOrientationFromLidar and pairOrientationFromStereo (pair_orientation.hpp) in their steps, for
// a caller that splits the work among threads (fast/pair_orientation.cpp): the LiDAR samples tested
// are every step-th, test t the sample t * step; the stereo grid's rows are independent. Votes on
// ranges of either are counts, so their sum is the same for any split.

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

/// The stereo check's grid of left-image pixels: rows firstY + i * stepY (i < rows), columns
/// from max(radius, stepX / 2) in steps of stepX; disparities [dMin, dMax] both ways.
struct StereoGrid {
  int width = 0, height = 0;
  int dMin = 0, dMax = 0;
  int stepX = 1, stepY = 1, firstY = 0, rows = 0;
};
StereoGrid stereoGrid(const GrayImageView& left, int minDisparity, int numDisparities);

/// One range's working rows (the right image's 7 rows, their column sums and patch means).
struct StereoGridScratch {
  std::vector<float> rows, rightMean, columnSum;
};

/// The votes of grid rows [begin, end) added to `votes`.
void voteAtGridRows(const GrayImageView& left, const GrayImageView& right, const StereoGrid& grid, int begin, int end,
                    PairOrientation& votes, StereoGridScratch& scratch);

}  // namespace lidar_sgm
