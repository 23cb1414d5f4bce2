#pragma once
/// @file report.hpp  Evaluation results: data model, median summaries, Markdown tables, JSON,
/// and an atomic text writer.

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/metrics.hpp"

namespace lidar_sgm {
namespace evaluation {

using eval::DisparityMetrics;

/// One method's scores on one frame.
struct MethodResult {
  std::string method;
  DisparityMetrics metrics;
  double milliseconds = 0;  ///< run time of the method on the frame
};

struct FrameResult {
  std::string dataset, frame;
  std::vector<MethodResult> methods;
};

/// Everything one protocol measured.
struct ProtocolResult {
  std::string protocol;
  std::string description;
  std::vector<FrameResult> frames;
  /// Parameter sweeps: name -> (alpha, median metrics over the frames at that alpha).
  std::vector<std::pair<std::string, std::vector<std::pair<double, DisparityMetrics>>>> sweeps;
};

/// Median of a list of values; for an even count the mean of the two middle values. 0 if empty.
double medianOf(std::vector<double> values);

/// Per-field median of correct, rmse, d1, d1Est, density; gtPixels and estimatedPixels are
/// summed (the pixel counts behind the medians). Empty input gives default metrics.
DisparityMetrics medianOver(const std::vector<DisparityMetrics>& metrics);

/// Per method (in order of first appearance): its medians over the protocol's frames, and the
/// median run time [ms].
std::vector<std::pair<std::string, std::pair<DisparityMetrics, double>>> methodMedians(const ProtocolResult& result);

/// Markdown: one row per frame x method (frame | method | correct % | RMSE px | D1 % |
/// density %), then a "median" row per method over the frames; shares in percent with 2
/// decimals, RMSE with 3. Each sweep follows as its own table (alpha | the same columns).
/// Frames are named "dataset/frame" (frame alone when dataset is empty).
std::string markdownTable(const ProtocolResult& result);

/// Every figure, machine-readable. Shares (correct, d1, d1_est, density) are fractions in
/// [0, 1] as in DisparityMetrics, rmse in px, ms in milliseconds:
/// {"protocols":[{"protocol","description","frames":[{"dataset","frame","methods":[{"method",
/// "correct","rmse","d1","d1_est","density","gt_pixels","estimated_pixels","ms"}]}],
/// "medians":{method:{... same fields}},"sweeps":{name:[{"alpha","correct","rmse",...}]}}]}
nlohmann::json toJson(const std::vector<ProtocolResult>& results);

/// Writes `text` to a temporary file in the same directory and renames it over `path`, so a
/// crash never leaves a partial file. Throws std::runtime_error naming `path` when its directory
/// does not exist or writing fails (no temporary file is left behind).
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace evaluation
}  // namespace lidar_sgm
