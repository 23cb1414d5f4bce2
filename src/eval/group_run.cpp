#include "lidar_sgm/eval/group_run.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "frame_pictures.hpp"
#include "lidar_sgm/eval/alpha_sweep.hpp"
#include "lidar_sgm/eval/ground_truth_cloud.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

/// All results of one frame: per method, and the sweep (alpha -> metrics).
struct FrameRun {
  FrameResult result;
  std::vector<MethodResult> sweep;  ///< the fused method at each alpha of options.alphas
  std::vector<std::pair<Method, Image<std::int16_t>>> disparities;  ///< kept for the pictures
  std::string fusedRange;  ///< the range the fused method at the paper's alpha matched with, for the log
};

/// Every metric of one method's output on one frame.
/// With `curves`, also the confidence curves, from the output's disparity before the minimum
/// confidence dropped any pixel (MethodOutput::allDisparity): without a new run. With
/// `groundTruthCloud`, also the 3D score of the output's cloud.
MethodResult score(const Method& method, const EvalFrame& f, const MethodOutput& out, bool curves,
                   const GroundTruthCloud* groundTruthCloud, const Image<std::uint8_t>& offTheScan) {
  const Image<std::int16_t>& d = out.disparity;
  MethodResult result;
  result.method = method;
  result.metrics = evaluateDisparity(d.view(), f.groundTruth.view(), f.exclude.view());
  result.milliseconds = out.milliseconds;
  result.minDisparity = out.range.minDisparity;
  result.numDisparities = out.range.numDisparities;
  result.rangeFromLidar = out.range.fromLidar;
  CloudScoring scoring;
  scoring.denseGroundTruth = f.denseGroundTruth;  // P3: a point on the sky is wrong
  result.cloud = evaluateCloud(d.view(), f.groundTruth.view(), f.exclude.view(), f.focalBaseline, scoring);
  result.depth = evaluateDepth(d.view(), f.groundTruth.view(), f.exclude.view(), f.focalBaseline, scoring);
  if (!f.objectMap.empty()) {
    result.objectSplit = evaluateObjectSplit(d.view(), f.groundTruth.view(), f.objectMap.view());
    result.objectSplitOnScan =
        offTheScan.empty() ? result.objectSplit
                           : evaluateObjectSplit(d.view(), f.groundTruth.view(), f.objectMap.view(), offTheScan.view());
  }
  if (!f.inputPixels.empty()) result.uncovered = evaluateDisparity(d.view(), f.groundTruth.view(), f.inputPixels.view());
  if (groundTruthCloud) result.cloud3d = groundTruthCloud->score(d.view());
  if (curves && !out.confidence.empty()) {
    result.confidence = confidenceCurves(out.allDisparity.view(), out.confidence.view(), f.groundTruth.view(),
                                         f.exclude.view(), f.focalBaseline, scoring);
  }
  return result;
}

FrameRun runFrame(const EvalFrame& frame, const std::vector<Method>& methods, const GroupRunOptions& options,
                  const DensifierConfig& config) {
  FrameRun run;
  run.result.dataset = frame.dataset;
  run.result.frame = frame.name;
  // The GT's cloud and its kd-tree, once for every method of the frame.
  const std::optional<GroundTruthCloud> groundTruthCloud =
      frame.calibration ? std::optional<GroundTruthCloud>(std::in_place, frame) : std::nullopt;
  const GroundTruthCloud* cloud3d = groundTruthCloud ? &*groundTruthCloud : nullptr;
  if (!frame.objectMap.empty() && !frame.lidarSparse.empty()) {
    run.result.scanAgreement = scanAgreement(frame.lidarSparse.view(), frame.groundTruth.view(), frame.objectMap.view());
  }
  const Image<std::uint8_t> offTheScan = offTheScanPixels(frame.objectMap.view(), run.result.scanAgreement);
  for (const Method& m : methods) {
    MethodOutput out =
        runMethod(m, frame, config, options.fixedNumDisparities);
    run.result.methods.push_back(score(m, frame, out, true, cloud3d, offTheScan));
    run.disparities.emplace_back(m, std::move(out.disparity));
  }
  for (double alpha : options.alphas) {
    const Method fused{MethodKind::FusedSgm, alpha};
    MethodOutput out =
        runMethod(fused, frame, config, options.fixedNumDisparities);
    const bool paperAlpha = std::abs(alpha - kPaperAlpha) < 1e-9;
    // Only the table's entry is judged and scored in 3D: at every alpha, the curves would cost a
    // second sweep and the 3D score (a kd-tree per cloud) as much as the matching.
    run.sweep.push_back(score(fused, frame, out, paperAlpha, paperAlpha ? cloud3d : nullptr, offTheScan));
    if (paperAlpha) {
      run.fusedRange = out.range.describe();
      run.result.methods.push_back(run.sweep.back());
      run.sweep.back().confidence = {};  // the sweep's best-alpha entry has none (MethodResult)
      run.disparities.emplace_back(fused, std::move(out.disparity));
    }
  }
  return run;
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<Method> baseMethods() {
  return {{MethodKind::StereoSgm, 0.0}, {MethodKind::LidarSgm, 1.0}, {MethodKind::OpenCvSgbm, 0.0},
          {MethodKind::Morphological, 0.0}};
}

std::string slug(const std::string& text) {
  std::string s;
  for (char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
  return s;
}

ProtocolResult runGroup(const FrameGroup& group, const GroupRunOptions& options) {
  if (options.alphas.empty()) throw std::invalid_argument("runGroup: the alpha sweep is empty");
  const int threads = std::max(1, options.threads);
  const int workers = std::max(1, std::min(threads, static_cast<int>(group.frames.size())));
  DensifierConfig config = options.config;
  config.matcher.threads = std::max(1, threads / workers);
  std::vector<FrameRun> runs(group.frames.size());
  std::atomic<std::size_t> next{0};
  std::mutex printMutex;
  std::size_t done = 0;  // progress, counted under printMutex
  std::vector<std::string> errors(group.frames.size());
  auto worker = [&]() {
    for (std::size_t i = next++; i < group.frames.size(); i = next++) {
      try {
        const auto start = std::chrono::steady_clock::now();
        runs[i] = runFrame(group.frames[i], group.methods, options, config);
        if (!options.picturesDir.empty()) writeFramePictures(options.picturesDir, group.frames[i], runs[i].disparities);
        runs[i].disparities.clear();  // the pictures are written; the memory is not needed
        std::lock_guard<std::mutex> lock(printMutex);
        std::printf("  [%zu/%zu] %s / %s [done, %.0f ms; fused range %s]\n", ++done, group.frames.size(),
                    group.frames[i].dataset.c_str(), group.frames[i].name.c_str(), millisecondsSince(start),
                    runs[i].fusedRange.c_str());
        std::fflush(stdout);
      } catch (const std::exception& e) {
        errors[i] = group.frames[i].name + ": " + e.what();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < workers; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  for (const std::string& e : errors) {
    if (!e.empty()) throw std::runtime_error(group.name + ", frame " + e);
  }

  ProtocolResult result;
  result.protocol = group.name;
  result.description = group.description;
  AlphaSweep sweep;
  for (std::size_t a = 0; a < options.alphas.size(); ++a) {
    std::vector<DisparityMetrics> perFrame;
    for (const FrameRun& r : runs) perFrame.push_back(r.sweep[a].metrics);
    sweep.medians.emplace_back(options.alphas[a], medianOver(perFrame));
  }
  const std::size_t best = bestAlphaIndex(sweep.medians);
  for (FrameRun& run : runs) {
    FrameResult frame = std::move(run.result);
    MethodResult bestResult = run.sweep[best];
    bestResult.milliseconds = 0.0;  // the same run as the fused method at its alpha: not timed twice
    bestResult.bestAlpha = true;
    frame.methods.push_back(bestResult);
    result.frames.push_back(std::move(frame));
  }
  result.sweeps.push_back(std::move(sweep));
  return result;
}

}  // namespace eval
}  // namespace lidar_sgm
