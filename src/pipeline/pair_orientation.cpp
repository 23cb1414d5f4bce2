#include "lidar_sgm/pipeline/pair_orientation.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "pipeline/pair_orientation_votes.hpp"
#include "patch_match.hpp"

namespace lidar_sgm {
namespace {

constexpr double kClearlyBetter = 0.8;     ///< a vote needs a cost below 80 % of the other's
constexpr std::size_t kMinDecided = 30;    ///< fewer decided patches prove nothing
constexpr std::size_t kMaxLidarTests = 4000;
constexpr int kGridColumns = 24;           ///< the stereo-only grid: 24 columns by 16 rows
constexpr int kGridRows = 16;              ///< of pixels, whatever the image's size

using patch::Gray;
using patch::inside;
using patch::kRadius;
using patch::patchMean;
using patch::patchTexture;
using patch::zsad;

void vote(PairOrientation& votes, double given, double swapped) {
  ++votes.tested;
  if (given < kClearlyBetter * swapped) ++votes.givenWins;
  if (swapped < kClearlyBetter * given) ++votes.swappedWins;
}

bool usable(const GrayImageView& left, const GrayImageView& right) {
  return !left.empty() && !right.empty() && left.width() == right.width() && left.height() == right.height() &&
         left.gray8.empty() == right.gray8.empty();
}

}  // namespace

bool PairOrientation::looksSwapped() const {
  return givenWins + swappedWins >= kMinDecided && swappedWins >= 2 * givenWins;
}

std::string PairOrientation::describe() const {
  const std::string where = fromLidar ? " LiDAR points" : " textured pixels";
  return "at " + std::to_string(swappedWins) + " of " + std::to_string(tested) + where +
         " the left image matches the right one at x + d (as a swapped pair would), at " +
         std::to_string(givenWins) + " at x - d (as given)";
}

std::size_t lidarTestStep(std::size_t samples) { return std::max<std::size_t>(1, samples / kMaxLidarTests); }

std::size_t lidarTestCount(std::size_t samples) {
  const std::size_t step = lidarTestStep(samples);
  return (samples + step - 1) / step;
}

bool pairVotable(const GrayImageView& left, const GrayImageView& right) { return usable(left, right); }

void voteAtLidarSamples(const GrayImageView& leftView, const GrayImageView& rightView,
                        const std::vector<LidarSample>& lidar, std::size_t begin, std::size_t end,
                        PairOrientation& votes) {
  const Gray left(leftView);
  const Gray right(rightView);
  const std::size_t step = lidarTestStep(lidar.size());
  for (std::size_t test = begin; test < end; ++test) {
    const LidarSample& s = lidar[test * step];
    const int d = (s.disparity16 + 8) / 16;
    if (d < 3 || !inside(left, s.x, s.y) || !inside(right, s.x - d, s.y) || !inside(right, s.x + d, s.y)) continue;
    const double mean = patchMean(left, s.x, s.y);
    if (patchTexture(left, s.x, s.y, mean) < left.flatness()) continue;
    vote(votes, zsad(left, mean, right, s.x, s.x - d, s.y), zsad(left, mean, right, s.x, s.x + d, s.y));
  }
}

PairOrientation pairOrientationFromLidar(const GrayImageView& leftView, const GrayImageView& rightView,
                                         const std::vector<LidarSample>& lidar) {
  PairOrientation votes;
  votes.fromLidar = true;
  if (!usable(leftView, rightView)) return votes;
  voteAtLidarSamples(leftView, rightView, lidar, 0, lidarTestCount(lidar.size()), votes);
  return votes;
}

StereoGrid stereoGrid(const GrayImageView& leftView, int minDisparity, int numDisparities) {
  StereoGrid grid;
  const Gray left(leftView);
  grid.width = left.width();
  grid.height = left.height();
  grid.dMin = std::max(minDisparity, 1);
  grid.dMax = minDisparity + numDisparities - 1;
  grid.stepX = std::max(1, grid.width / kGridColumns);
  grid.stepY = std::max(1, grid.height / kGridRows);
  grid.firstY = std::max(kRadius, grid.stepY / 2);
  const int lastY = grid.height - kRadius;  // exclusive
  grid.rows = lastY > grid.firstY ? (lastY - grid.firstY + grid.stepY - 1) / grid.stepY : 0;
  return grid;
}

void voteAtGridRows(const GrayImageView& leftView, const GrayImageView& rightView, const StereoGrid& grid, int begin,
                    int end, PairOrientation& votes, StereoGridScratch& scratch) {
  const Gray left(leftView);
  const Gray right(rightView);
  const int width = grid.width;
  constexpr int kSide = 2 * kRadius + 1;
  // Per grid row, the right image's 7 rows and each column's patch mean, read once: a pixel
  // then costs 2 x numDisparities patch differences (~2 ms on a KITTI frame for 128).
  std::vector<float>& rows = scratch.rows;
  std::vector<float>& rightMean = scratch.rightMean;
  std::vector<float>& columnSum = scratch.columnSum;
  rows.resize(static_cast<std::size_t>(kSide) * width);
  rightMean.resize(static_cast<std::size_t>(width));
  columnSum.resize(static_cast<std::size_t>(width));
  std::array<float, kSide * kSide> patch{};
  for (int row = begin; row < end; ++row) {
    const int y = grid.firstY + row * grid.stepY;
    std::fill(columnSum.begin(), columnSum.end(), 0.0f);
    for (int j = 0; j < kSide; ++j) {
      for (int x = 0; x < width; ++x) {
        const float v = static_cast<float>(right.at(x, y - kRadius + j));
        rows[static_cast<std::size_t>(j) * width + x] = v;
        columnSum[static_cast<std::size_t>(x)] += v;
      }
    }
    for (int x = kRadius; x < width - kRadius; ++x) {
      float sum = 0.0f;
      for (int i = -kRadius; i <= kRadius; ++i) sum += columnSum[static_cast<std::size_t>(x + i)];
      rightMean[static_cast<std::size_t>(x)] = sum / (kSide * kSide);
    }
    const auto cost = [&](int xr) {  // zero-mean SAD against the right patch at column xr
      float sad = 0.0f;
      const float mean = rightMean[static_cast<std::size_t>(xr)];
      for (int j = 0; j < kSide; ++j) {
        const float* r = &rows[static_cast<std::size_t>(j) * width + xr - kRadius];
        for (int i = 0; i < kSide; ++i) sad += std::abs(patch[static_cast<std::size_t>(j * kSide + i)] - (r[i] - mean));
      }
      return sad;
    };
    for (int x = std::max(kRadius, grid.stepX / 2); x < width - kRadius; x += grid.stepX) {
      const double leftMean = patchMean(left, x, y);
      if (patchTexture(left, x, y, leftMean) < left.flatness()) continue;
      const float mean = static_cast<float>(leftMean);
      for (int j = 0; j < kSide; ++j) {
        for (int i = 0; i < kSide; ++i) {
          patch[static_cast<std::size_t>(j * kSide + i)] =
              static_cast<float>(left.at(x - kRadius + i, y - kRadius + j)) - mean;
        }
      }
      // The same disparities both ways, so that neither side has more chances.
      float bestGiven = std::numeric_limits<float>::max();
      float bestSwapped = std::numeric_limits<float>::max();
      for (int d = grid.dMin; d <= grid.dMax && x - d >= kRadius && x + d < width - kRadius; ++d) {
        bestGiven = std::min(bestGiven, cost(x - d));
        bestSwapped = std::min(bestSwapped, cost(x + d));
      }
      if (bestGiven != std::numeric_limits<float>::max()) vote(votes, bestGiven, bestSwapped);
    }
  }
}

PairOrientation pairOrientationFromStereo(const GrayImageView& leftView, const GrayImageView& rightView,
                                          int minDisparity, int numDisparities) {
  PairOrientation votes;
  if (!usable(leftView, rightView)) return votes;
  const StereoGrid grid = stereoGrid(leftView, minDisparity, numDisparities);
  StereoGridScratch scratch;
  voteAtGridRows(leftView, rightView, grid, 0, grid.rows, votes, scratch);
  return votes;
}

std::string swappedPairMessage(const PairOrientation& votes) {
  return "the stereo pair looks swapped: " + votes.describe() +
         ". Were the left and right images given the wrong way round? Give them the other way, or turn the pair "
         "check off to go on anyway (the tools' -no_pair_check, Densifier::setPairCheck(false))";
}

}  // namespace lidar_sgm
