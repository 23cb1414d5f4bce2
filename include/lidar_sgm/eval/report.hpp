#pragma once
/// @file report.hpp  Evaluation results: data model, median summaries, Markdown tables, JSON,
/// and an atomic text writer.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/cloud_distance.hpp"
#include "lidar_sgm/eval/cloud_metrics.hpp"
#include "lidar_sgm/eval/confidence_curves.hpp"
#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/scan_agreement.hpp"

namespace lidar_sgm {
namespace eval {

/// One method's scores on one frame.
struct MethodResult {
  Method method;
  DisparityMetrics metrics;
  double milliseconds = 0;  ///< run time of the method on the frame
  /// The group's best alpha of the sweep (chosen on the same frames: an upper bound), reported
  /// beside the same method at the paper's alpha.
  bool bestAlpha = false;
  /// The search range [minDisparity, minDisparity + numDisparities) the method matched with, and
  /// whether it came from the LiDAR; numDisparities 0 where none (IP-Basic, the medians).
  int minDisparity = 0;
  int numDisparities = 0;
  bool rangeFromLidar = false;
  CloudMetrics cloud{};  ///< the same output scored as a cloud
  DepthMetrics depth{};  ///< and as a depth map (KITTI depth completion)
  /// The method's confidence judged (confidence_curves.hpp); empty where it has none, and for
  /// the sweep's best alpha (the fused method is judged at the paper's alpha).
  ConfidenceCurves confidence{};
  /// Frames with an object map (the KITTI142 protocol): the paper's Table II figures; for the
  /// medians, over all the frames' pixels (counts summed, then the shares: KITTI's devkit, whose
  /// script filled the paper's Table II, sums its error and pixel counts over the images).
  std::optional<ObjectSplitMetrics> objectSplit{};
  /// For the medians only: the same figures as the mean of the frames' shares (each frame weighs
  /// the same, however many object pixels it has).
  std::optional<ObjectSplitMetrics> objectSplitFrameMean{};
  /// The same without the pixels of the frame's objects whose GT lies off their own scan
  /// (scan_agreement.hpp); equal to objectSplit on a frame without such an object.
  std::optional<ObjectSplitMetrics> objectSplitOnScan{};
  /// Frames that score their input pixels too (KITTI142): the metrics on the GT pixels that no
  /// input point covers, where the GT cannot favour a method for having been given the answer.
  std::optional<DisparityMetrics> uncovered{};
  /// Frames with a calibration (KITTI142): the output's cloud against the GT's cloud in 3D
  /// (ground_truth_cloud.hpp), for the table's methods; not for the sweep's other alphas. For
  /// the medians, medianCloudDistance over the frames.
  std::optional<CloudDistanceScore> cloud3d{};
};

/// Same method and the same role (sweep best or not): what the medians are grouped by.
bool sameEntry(const MethodResult& a, const MethodResult& b);

/// For tables and plots: displayName(method), or "LiDAR-SGM (best alpha 0.9)" for the sweep's best.
std::string label(const MethodResult& result);

struct FrameResult {
  std::string dataset, frame;
  std::vector<MethodResult> methods;
  /// Frames with an object map: each object's GT against the frame's scan (scan_agreement.hpp).
  std::vector<ObjectScanAgreement> scanAgreement{};
};

/// A method over a range of alphas: (alpha, median metrics over the frames at that alpha).
struct AlphaSweep {
  MethodKind kind = MethodKind::FusedSgm;
  std::vector<std::pair<double, DisparityMetrics>> medians;
};

/// Everything one protocol measured.
struct ProtocolResult {
  std::string protocol;
  std::string description;
  std::vector<FrameResult> frames;
  std::vector<AlphaSweep> sweeps;
};

/// Median of a list of values; for an even count the mean of the two middle values. 0 if empty.
double medianOf(std::vector<double> values);

/// Per-field median of correct, rmse, d1, d1Est, density; gtPixels and estimatedPixels are
/// summed (the pixel counts behind the medians). Empty input gives default metrics.
DisparityMetrics medianOver(const std::vector<DisparityMetrics>& metrics);

/// The same for the cloud metrics: per-field medians of precision, completeness and F at each
/// tau (so the median F is not the F of the median precision and completeness); counts summed.
CloudMetrics medianCloud(const std::vector<CloudMetrics>& metrics);

/// The same for the depth metrics: per-field medians of RMSE, MAE, iRMSE, iMAE and density.
DepthMetrics medianDepth(const std::vector<DepthMetrics>& metrics);

/// Per method entry (sameEntry; in order of first appearance): its medians over the protocol's
/// frames (disparity, cloud and depth metrics), with the median run time as `milliseconds`.
std::vector<MethodResult> methodMedians(const ProtocolResult& result);

/// Markdown: one row per frame x method (frame | method | correct % | RMSE px | D1 % |
/// density %), then a "median" row per method over the frames; shares in percent with 2
/// decimals, RMSE with 3. Each sweep follows as its own table (alpha | the same columns).
/// Frames are named "dataset/frame" (frame alone when dataset is empty). Between the two come a
/// "cloud" table (frame | method | precision, completeness, F-score at tau 5 % and 3 %, in
/// percent) and a "depth" table (frame | method | RMSE mm | MAE mm | iRMSE 1/km | iMAE 1/km |
/// with estimate %), rows and medians as in the first.
std::string markdownTable(const ProtocolResult& result);

/// Per-field means of the object split over frames (counts summed).
ObjectSplitMetrics meanObjectSplit(const std::vector<ObjectSplitMetrics>& frames);

/// The object split over all the frames' pixels, as KITTI's devkit summarises it: the counts
/// summed over the frames, then the shares (a frame weighs by its pixels).
ObjectSplitMetrics pooledObjectSplit(const std::vector<ObjectSplitMetrics>& frames);

/// The paper's tables for a protocol whose frames have an object map (KITTI142), from the
/// medians of `result` beside the paper's own figures: Table I (median correct and RMSE, and
/// correct on the GT pixels no input point covers) and Table II (error among the estimated pixels,
/// background / foreground / total, and density, over all the frames' pixels as KITTI's devkit
/// counts them; then the mean of the frames' shares). Empty when no method has the object split.
std::string paperTablesMarkdown(const ProtocolResult& result);

/// Every figure, machine-readable. Methods are named by their stable id (methodId), with
/// "alpha" where the method has one, "best_alpha" for the sweep's best, and "name" (the display
/// name, for people only). Shares (correct, d1, d1_est, density) are fractions in [0, 1] as in
/// DisparityMetrics, rmse in px, ms in milliseconds:
/// {"protocols":[{"protocol","description","frames":[{"dataset","frame","methods":[{"method",
/// ["alpha",] "best_alpha","name","correct","rmse","d1","d1_est","density","gt_pixels",
/// "estimated_pixels","ms",["disparity_range":{"min","num","from_lidar"},]"cloud":{"points","gt_pixels","tau_3":{"precision","completeness",
/// "f_score"},"tau_5":{...}},"depth":{"rmse_mm","mae_mm","irmse_per_km","imae_per_km","density",
/// "gt_pixels","estimated_pixels"}[,"object_split":{"background","foreground","total","density",
/// "gt_pixels","foreground_pixels"}][,"uncovered":{the disparity metrics}][,"cloud_3d":{cloudDistanceJson}]}]}],"medians":[{... same fields}],"sweeps":{method id:[{"alpha",
/// "correct","rmse",...}]}}]} (the sweeps hold the disparity metrics only).
nlohmann::json toJson(const std::vector<ProtocolResult>& results);


}  // namespace eval
}  // namespace lidar_sgm
