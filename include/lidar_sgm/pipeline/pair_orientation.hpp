#pragma once
/// @file pair_orientation.hpp  Whether a stereo pair was given the wrong way round.
///
/// A swapped pair (the right camera's image as the left one) matches nothing at x - d, where a
/// rectified pair's matches are, and everything at x + d. SGM on it still fills most pixels,
/// with wrong depths and the other camera's colors, so the Densifier refuses it unless told to
/// go on. Two witnesses: the LiDAR, whose disparities say where each match must be; without it,
/// the pair alone, whose best matches fall on the wrong side.

#include <cstddef>
#include <string>
#include <vector>

#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {

/// Votes of textured patches for either orientation of the pair.
struct PairOrientation {
  bool fromLidar = false;        ///< votes at LiDAR points (else at a grid of the left image)
  std::size_t tested = 0;        ///< patches scored both ways
  std::size_t givenWins = 0;     ///< clearly better as given (x - d)
  std::size_t swappedWins = 0;   ///< clearly better swapped (x + d)

  /// Swapped wins at least twice as often as given, over at least 30 decided patches: a pair
  /// given the right way round has the given orientation win at most points (KITTI: > 80 %).
  bool looksSwapped() const;
  /// "at 812 of 1000 LiDAR points the left image matches the right one at x + d (swapped), at
  /// 41 at x - d (as given)".
  std::string describe() const;
};

/// Votes at the LiDAR samples of `lidar` (pixel and disparity in the left image): a 7x7
/// zero-mean SAD between the left patch and the right one at x - d (as given) and at x + d
/// (swapped). Samples below 3 px of disparity or whose patches leave the image are not tested;
/// at most about 4000 samples, evenly spread, are.
PairOrientation pairOrientationFromLidar(const GrayImageView& left, const GrayImageView& right,
                                         const std::vector<LidarSample>& lidar);

/// Without LiDAR: at a grid of textured left-image pixels, the best match in the right image
/// over disparities [minDisparity, minDisparity + numDisparities) at x - d and at x + d.
PairOrientation pairOrientationFromStereo(const GrayImageView& left, const GrayImageView& right, int minDisparity,
                                          int numDisparities);

/// The message of a refused pair: what was seen, the likely swap, and how to go on anyway.
std::string swappedPairMessage(const PairOrientation& votes);

}  // namespace lidar_sgm
