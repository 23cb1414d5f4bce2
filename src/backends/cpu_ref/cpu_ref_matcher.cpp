#include "backends/cpu_ref/cpu_ref_matcher.hpp"

#include <chrono>
#include <utility>

#include "backends/common/gated_stages.hpp"
#include "backends/common/lidar_search_windows.hpp"
#include "backends/common/lidar_weights.hpp"
#include "backends/common/stages.hpp"

namespace lidar_sgm {
namespace cpu_ref {

/// Splits a frame's wall time into its stages, one lap each.
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

}  // namespace cpu_ref

namespace {

void census(const GrayImageView& image, CensusType type, Image<std::uint64_t>& out) {
  out.resize(image.width(), image.height());
  if (!image.gray8.empty()) {
    cpu_ref::censusTransform(image.gray8, type, out.view());
  } else {
    cpu_ref::censusTransform(image.gray16, type, out.view());
  }
}

}  // namespace

std::unique_ptr<MatcherBackend> createCpuRefMatcher() { return std::make_unique<CpuRefMatcher>(); }

void CpuRefMatcher::run(const FramePlan& plan, const FrameInputs& in, ImageView<std::int16_t> disparity,
                        FrameResults& out) {
  const Parameters& p = plan.params;
  cpu_ref::StageClock clock;
  const MatchingCostVolume& cost = matchingCost(plan, in, clock, out);

  if (plan.gatedSearch) {
    // The LiDAR gate: each pixel's window, and the matching cost kept on the windows only.
    lidarSearchWindows(*in.lidar, plan.minDisparity, plan.D, p.gatedSearchRows, p.gatedSearchMargin, windows_);
    windowedCost_.resize(windows_);
    cpu_ref::restrictToWindows(cost, windowedCost_);
    cpu_ref::aggregatePaths(windowedCost_, p.P1, p.P2, p.paths, windowedSum_);
  } else {
    sum_.resize(plan.width, plan.height, plan.D);
    cpu_ref::aggregatePaths(cost, p.P1, p.P2, p.paths, sum_);
  }
  out.timings.aggregatePaths = clock.lapMs();

  rawDisparity_.resize(plan.width, plan.height);
  bestIndex_.resize(plan.width, plan.height);
  const SelectedDisparity selected{rawDisparity_.view(), bestIndex_.view()};
  if (plan.gatedSearch) {
    cpu_ref::selectDisparity(windowedSum_, plan.minDisparity, p.uniquenessRatio, p.subpixel, selected);
  } else {
    cpu_ref::selectDisparity(sum_, plan.minDisparity, p.uniquenessRatio, p.subpixel, selected);
  }
  out.timings.selectDisparity = clock.lapMs();

  confidenceInputs(plan, out.confidenceInputs);
  if (plan.lrCheck) {
    leftRightCheck(plan, in.lidar);
    out.timings.leftRightCheck = clock.lapMs();
  }

  cpu_ref::medianFilter(rawDisparity_.view(), p.medianSize, disparity);
  out.timings.medianFilter = clock.lapMs();
}

const MatchingCostVolume& CpuRefMatcher::matchingCost(const FramePlan& plan, const FrameInputs& in,
                                                      cpu_ref::StageClock& clock, FrameResults& out) {
  out.support.resize(plan.width, plan.height);
  out.support.fill(0);
  const MatchingCostVolume* camera = plan.useCameras() ? &cameraCost(plan, in, clock, out.timings) : nullptr;
  if (!plan.useLidar) return *camera;
  lidarCost(plan, *in.lidar, out.support.view());
  out.timings.lidarCost = clock.lapMs();
  if (plan.mode != MatchMode::Fused) return lidarCost_;
  const MatchingCostVolume& fused = fuseCosts(plan, *in.lidar, *camera, std::as_const(out.support).view());
  out.timings.fuseCosts = clock.lapMs();
  return fused;
}

const MatchingCostVolume& CpuRefMatcher::cameraCost(const FramePlan& plan, const FrameInputs& in,
                                                    cpu_ref::StageClock& clock, StageTimings& timings) {
  const CensusType type = plan.params.censusType;
  census(in.left, type, leftCensus_);
  census(in.right, type, rightCensus_);
  if (plan.upCamera()) census(in.up, type, upCensus_);
  timings.census = clock.lapMs();
  stereoCost_.resize(plan.width, plan.height, plan.D);
  cpu_ref::censusCost(leftCensus_.view(), rightCensus_.view(), type, plan.minDisparity, stereoCost_);
  timings.censusCost = clock.lapMs();
  if (!plan.upCamera()) return stereoCost_;
  verticalCost_.resize(plan.width, plan.height, plan.D);
  cpu_ref::verticalCensusCost(leftCensus_.view(), upCensus_.view(), type, plan.ratio16, plan.minDisparity,
                              verticalCost_);
  cameraCost_.resize(plan.width, plan.height, plan.D);
  cpu_ref::combineCameraCosts(stereoCost_, verticalCost_, cameraCost_);
  timings.verticalCensusCost = clock.lapMs();
  return cameraCost_;
}

void CpuRefMatcher::lidarCost(const FramePlan& plan, const LidarPoints& lidar, ImageView<std::uint8_t> support) {
  const Parameters& p = plan.params;
  if (tableSigma_ != p.sigma || tableCap_ != p.lidarCostCap) {
    table_ = LidarCostTable(p.sigma, p.lidarCostCap);
    tableSigma_ = p.sigma;
    tableCap_ = p.lidarCostCap;
  }
  lidarCost_.resize(plan.width, plan.height, plan.D);
  cpu_ref::lidarCost(lidar, table_, plan.minDisparity, lidarCost_, support);
}

const MatchingCostVolume& CpuRefMatcher::fuseCosts(const FramePlan& plan, const LidarPoints& lidar,
                                                   const MatchingCostVolume& cameraCost,
                                                   ImageView<const std::uint8_t> support) {
  fusedCost_.resize(plan.width, plan.height, plan.D);
  // The LiDAR weight of each pixel, alphaWeight(alpha) everywhere with a fixed alpha.
  lidarWeights_.resize(plan.width, plan.height);
  lidarWeights(lidar, plan.params, lidarWeights_.view());
  cpu_ref::fuseCosts(lidarCost_, cameraCost, support, std::as_const(lidarWeights_).view(),
                     plan.params.stereoCostWithoutLidar, fusedCost_);
  return fusedCost_;
}

void CpuRefMatcher::confidenceInputs(const FramePlan& plan, ConfidenceInputs& out) {
  if (plan.confidence) {
    out.margin.resize(plan.width, plan.height);
    out.bestCost.resize(plan.width, plan.height);
    if (plan.gatedSearch) {
      cpu_ref::peakRatioMargin(windowedSum_, std::as_const(bestIndex_).view(), out.margin.view(), out.bestCost.view());
    } else {
      cpu_ref::peakRatioMargin(sum_, std::as_const(bestIndex_).view(), out.margin.view(), out.bestCost.view());
    }
  }
  if (plan.confidenceLr) {
    rightDisparityIndex(plan);
    out.leftRightDifference.resize(plan.width, plan.height);
    cpu_ref::leftRightDifference(std::as_const(bestIndex_).view(), std::as_const(rightIndex_).view(),
                                 plan.minDisparity, out.leftRightDifference.view());
  }
}

void CpuRefMatcher::rightDisparityIndex(const FramePlan& plan) {
  rightIndex_.resize(plan.width, plan.height);
  if (plan.gatedSearch) {
    cpu_ref::rightDisparityIndex(windowedSum_, plan.minDisparity, rightIndex_.view());
  } else {
    cpu_ref::rightDisparityIndex(sum_, plan.minDisparity, rightIndex_.view());
  }
}

// With the up camera too, the check compares the left and right views (the right view's winners
// read diagonally from the same, C_S3-based, volume); the up view is not checked.
void CpuRefMatcher::leftRightCheck(const FramePlan& plan, const LidarPoints* lidar) {
  if (!plan.confidenceLr) rightDisparityIndex(plan);
  ImageView<const std::uint8_t> covered;
  if (plan.lrCheckTrustsLidar) {
    coverage_.resize(plan.width, plan.height);
    cpu_ref::lidarCoverage(*lidar, plan.params.lidarCoverageRows, coverage_.view());
    covered = coverage_.view();
  }
  cpu_ref::leftRightCheck(SelectedDisparity{rawDisparity_.view(), bestIndex_.view()}, rightIndex_.view(), covered,
                          plan.minDisparity, plan.params.disp12MaxDiff,
                          /*keepNoCounterpart=*/plan.lrCheckTrustsLidar);
}

}  // namespace lidar_sgm
