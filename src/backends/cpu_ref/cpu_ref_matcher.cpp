#include "backends/cpu_ref/cpu_ref_matcher.hpp"

#include <chrono>
#include <utility>

#include "backends/common/lidar_weights.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace {

class StageClock {
 public:
  double lapMs() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void census(const GrayImageView& image, CensusType type, Image<std::uint64_t>& out) {
  out.resize(image.width(), image.height());
  if (!image.gray8.empty()) {
    cpu_ref::censusTransform(image.gray8, type, out.view());
  } else {
    cpu_ref::censusTransform(image.gray16, type, out.view());
  }
}

}  // namespace

std::unique_ptr<Matcher> createCpuRefMatcher(const Parameters& params) {
  return std::make_unique<CpuRefMatcher>(params);
}

void CpuRefMatcher::run(const Parameters& params, const GrayImageView& left, const GrayImageView& right,
                        const LidarPoints* lidar, MatchMode mode, ImageView<std::int16_t> disparity) {
  runStages(params, left, right, nullptr, 0, lidar, mode, disparity);
}

void CpuRefMatcher::runWithUpCamera(const Parameters& params, const GrayImageView& left,
                                    const GrayImageView& right, const GrayImageView& up, int ratio16,
                                    const LidarPoints* lidar, MatchMode mode, ImageView<std::int16_t> disparity) {
  runStages(params, left, right, &up, ratio16, lidar, mode, disparity);
}

void CpuRefMatcher::runStages(const Parameters& params, const GrayImageView& left, const GrayImageView& right, const GrayImageView* up,
                              int ratio16, const LidarPoints* lidar, MatchMode mode,
                              ImageView<std::int16_t> disparity) {
  const Parameters& p = params;
  const int width = disparity.width;
  const int height = disparity.height;
  const int D = p.numDisparities;
  StageClock clock;

  support_.resize(width, height);
  support_.fill(0);
  // The camera cost: C_S with two cameras, C_S3 = (C_S + C_V + 1) >> 1 with the up camera.
  const MatchingCostVolume* cameraCost = &stereoCost_;
  if (mode != MatchMode::LidarOnly) {
    census(left, p.censusType, leftCensus_);
    census(right, p.censusType, rightCensus_);
    if (up != nullptr) census(*up, p.censusType, upCensus_);
    timings_.census = clock.lapMs();
    stereoCost_.resize(width, height, D);
    cpu_ref::censusCost(leftCensus_.view(), rightCensus_.view(), p.censusType, p.minDisparity, stereoCost_);
    timings_.censusCost = clock.lapMs();
    if (up != nullptr) {
      verticalCost_.resize(width, height, D);
      cpu_ref::verticalCensusCost(leftCensus_.view(), upCensus_.view(), p.censusType, ratio16, p.minDisparity,
                                  verticalCost_);
      cameraCost_.resize(width, height, D);
      cpu_ref::combineCameraCosts(stereoCost_, verticalCost_, cameraCost_);
      cameraCost = &cameraCost_;
      timings_.verticalCensusCost = clock.lapMs();
    }
  }
  if (mode != MatchMode::StereoOnly) {
    if (tableSigma_ != p.sigma || tableCap_ != p.lidarCostCap) {
      table_ = LidarCostTable(p.sigma, p.lidarCostCap);
      tableSigma_ = p.sigma;
      tableCap_ = p.lidarCostCap;
    }
    lidarCost_.resize(width, height, D);
    cpu_ref::lidarCost(*lidar, table_, p.minDisparity, lidarCost_, support_.view());
    timings_.lidarCost = clock.lapMs();
  }
  const MatchingCostVolume* cost = mode == MatchMode::StereoOnly ? cameraCost : &lidarCost_;
  if (mode == MatchMode::Fused) {
    fusedCost_.resize(width, height, D);
    // The LiDAR weight of each pixel, alphaWeight(alpha) everywhere with a fixed alpha.
    lidarWeights_.resize(width, height);
    lidarWeights(*lidar, p, lidarWeights_.view());
    cpu_ref::fuseCosts(lidarCost_, *cameraCost, support_.view(), std::as_const(lidarWeights_).view(),
                       p.stereoCostWithoutLidar, fusedCost_);
    cost = &fusedCost_;
    timings_.fuseCosts = clock.lapMs();
  }

  sum_.resize(width, height, D);
  cpu_ref::aggregatePaths(*cost, p.P1, p.P2, p.paths, sum_);
  timings_.aggregatePaths = clock.lapMs();

  rawDisparity_.resize(width, height);
  bestIndex_.resize(width, height);
  const SelectedDisparity selected{rawDisparity_.view(), bestIndex_.view()};
  cpu_ref::selectDisparity(sum_, p.minDisparity, p.uniquenessRatio, p.subpixel, selected);
  timings_.selectDisparity = clock.lapMs();

  // The confidence inputs that need S (core/confidence.hpp), read before the check invalidates.
  const bool confidenceLr = p.confidence && mode != MatchMode::LidarOnly;
  if (p.confidence) {
    confidenceInputs_.margin.resize(width, height);
    confidenceInputs_.bestCost.resize(width, height);
    cpu_ref::peakRatioMargin(sum_, std::as_const(bestIndex_).view(), confidenceInputs_.margin.view(),
                             confidenceInputs_.bestCost.view());
  }
  if (confidenceLr) {
    rightIndex_.resize(width, height);
    cpu_ref::rightDisparityIndex(sum_, p.minDisparity, rightIndex_.view());
    confidenceInputs_.leftRightDifference.resize(width, height);
    cpu_ref::leftRightDifference(std::as_const(bestIndex_).view(), std::as_const(rightIndex_).view(), p.minDisparity,
                                 confidenceInputs_.leftRightDifference.view());
  }

  // With the up camera too, the check still compares the left and right views (the right view's
  // winners read diagonally from the same, C_S3-based, volume); the up view is not checked.
  const bool lrCheck = mode == MatchMode::StereoOnly ? p.lrCheck : mode == MatchMode::Fused && p.lrCheck && p.lrCheckWithLidar;
  if (lrCheck) {
    if (!confidenceLr) {
      rightIndex_.resize(width, height);
      cpu_ref::rightDisparityIndex(sum_, p.minDisparity, rightIndex_.view());
    }
    ImageView<const std::uint8_t> support;
    if (mode == MatchMode::Fused) {
      coverage_.resize(width, height);
      cpu_ref::lidarCoverage(*lidar, p.lidarCoverageRows, coverage_.view());
      support = coverage_.view();
    }
    cpu_ref::leftRightCheck(selected, rightIndex_.view(), support, p.minDisparity, p.disp12MaxDiff,
                            /*keepNoCounterpart=*/mode == MatchMode::Fused);
    timings_.leftRightCheck = clock.lapMs();
  }

  cpu_ref::medianFilter(rawDisparity_.view(), p.medianSize, disparity);
  timings_.medianFilter = clock.lapMs();
}

}  // namespace lidar_sgm
