#include "report_format.hpp"
#include "lidar_sgm/eval/report.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "lidar_sgm/eval/cloud_distance_report.hpp"
#include "report_cloud.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

// ---------------------------------------------------------------------------------------------
// Markdown

/// A '|' inside a cell would end it.
std::string cell(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string frameName(const FrameResult& frame) {
  return frame.dataset.empty() ? frame.frame : frame.dataset + "/" + frame.frame;
}

/// correct % | RMSE px | D1 % | density %: shares in percent with 2 decimals, RMSE with 3
/// (sub-pixel differences between methods are in the third decimal).
std::string metricCells(const DisparityMetrics& m) {
  return fixed(100.0 * m.correct, 2) + " | " + fixed(m.rmse, 3) + " | " + fixed(100.0 * m.d1, 2) + " | " +
         fixed(100.0 * m.density, 2);
}

constexpr const char* kMetricHeader = "correct % | RMSE px | D1 % | density %";
constexpr const char* kMetricAlignment = "---: | ---: | ---: | ---:";

/// One row per frame x method, then one "median" row per method: `cells` gives a row's metric
/// cells from a MethodResult (the same layout for the disparity, cloud and depth tables).
template <typename Cells>
void appendFrameTable(std::ostringstream& out, const ProtocolResult& result, const std::vector<MethodResult>& medians,
                      const char* header, const char* alignment, Cells cells) {
  out << "| frame | method | " << header << " |\n";
  out << "| --- | --- | " << alignment << " |\n";
  for (const FrameResult& frame : result.frames) {
    for (const MethodResult& method : frame.methods) {
      out << "| " << cell(frameName(frame)) << " | " << cell(label(method)) << " | " << cells(method) << " |\n";
    }
  }
  for (const MethodResult& median : medians) {
    out << "| median | " << cell(label(median)) << " | " << cells(median) << " |\n";
  }
}

void appendSweepTable(std::ostringstream& out, const AlphaSweep& sweep) {
  out << "\nSweep over alpha: " << methodId(sweep.kind) << " (medians over frames)\n\n";
  out << "| alpha | " << kMetricHeader << " |\n";
  out << "| ---: | " << kMetricAlignment << " |\n";
  for (const auto& [alpha, metrics] : sweep.medians) out << "| " << fixed(alpha, 2) << " | " << metricCells(metrics) << " |\n";
}

// ---------------------------------------------------------------------------------------------
// JSON

nlohmann::json metricsJson(const DisparityMetrics& m) {
  return {{"correct", m.correct},   {"rmse", m.rmse},         {"d1", m.d1},
          {"d1_est", m.d1Est},      {"density", m.density},   {"gt_pixels", m.gtPixels},
          {"estimated_pixels", m.estimatedPixels}};
}

nlohmann::json methodJson(const MethodResult& method) {
  nlohmann::json entry = metricsJson(method.metrics);
  entry["cloud"] = cloudJson(method.cloud);
  entry["depth"] = depthJson(method.depth);
  entry["method"] = methodId(method.method.kind);
  if (method.method.usesAlpha()) entry["alpha"] = method.method.alpha;
  entry["best_alpha"] = method.bestAlpha;
  entry["name"] = label(method);
  entry["ms"] = method.milliseconds;
  const auto splitJson = [](const ObjectSplitMetrics& o) -> nlohmann::json {
    return {{"background", o.background}, {"foreground", o.foreground}, {"total", o.total},
            {"density", o.density},       {"gt_pixels", o.gtPixels}, {"foreground_pixels", o.foregroundPixels},
            {"estimated_background", o.estimatedBackground}, {"estimated_foreground", o.estimatedForeground},
            {"wrong_background", o.wrongBackground}, {"wrong_foreground", o.wrongForeground}};
  };
  if (method.objectSplit) entry["object_split"] = splitJson(*method.objectSplit);
  if (method.objectSplitFrameMean) entry["object_split_frame_mean"] = splitJson(*method.objectSplitFrameMean);
  if (method.objectSplitOnScan) entry["object_split_on_scan"] = splitJson(*method.objectSplitOnScan);
  if (method.uncovered) entry["uncovered"] = metricsJson(*method.uncovered);
  if (method.cloud3d) entry["cloud_3d"] = cloudDistanceJson(*method.cloud3d);
  if (method.numDisparities > 0) {
    entry["disparity_range"] = {
        {"min", method.minDisparity}, {"num", method.numDisparities}, {"from_lidar", method.rangeFromLidar}};
  }
  return entry;
}

nlohmann::json frameJson(const FrameResult& frame) {
  nlohmann::json methods = nlohmann::json::array();
  for (const MethodResult& method : frame.methods) methods.push_back(methodJson(method));
  nlohmann::json entry = {{"dataset", frame.dataset}, {"frame", frame.frame}, {"methods", methods}};
  if (!frame.scanAgreement.empty()) {
    nlohmann::json objects = nlohmann::json::array();
    for (const ObjectScanAgreement& a : frame.scanAgreement) {
      objects.push_back({{"object", a.object}, {"points", a.points}, {"median_scan_minus_gt_px", a.medianDifference},
                         {"off_the_scan", a.offTheScan()}});
    }
    entry["scan_agreement"] = objects;
  }
  return entry;
}

nlohmann::json protocolJson(const ProtocolResult& result) {
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameResult& frame : result.frames) frames.push_back(frameJson(frame));
  nlohmann::json medians = nlohmann::json::array();
  for (const MethodResult& median : methodMedians(result)) medians.push_back(methodJson(median));
  nlohmann::json sweeps = nlohmann::json::object();
  for (const AlphaSweep& sweep : result.sweeps) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [alpha, metrics] : sweep.medians) {
      nlohmann::json entry = metricsJson(metrics);
      entry["alpha"] = alpha;
      list.push_back(entry);
    }
    sweeps[methodId(sweep.kind)] = list;
  }
  return {{"protocol", result.protocol}, {"description", result.description}, {"frames", frames},
          {"medians", medians},          {"sweeps", sweeps}};
}

}  // namespace

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  if (values.size() % 2 == 1) return values[middle];
  return 0.5 * (values[middle - 1] + values[middle]);
}

DisparityMetrics medianOver(const std::vector<DisparityMetrics>& metrics) {
  DisparityMetrics result;
  if (metrics.empty()) return result;
  const auto field = [&metrics](double DisparityMetrics::*member) {
    std::vector<double> values;
    for (const DisparityMetrics& m : metrics) values.push_back(m.*member);
    return medianOf(values);
  };
  result.correct = field(&DisparityMetrics::correct);
  result.rmse = field(&DisparityMetrics::rmse);
  result.d1 = field(&DisparityMetrics::d1);
  result.d1Est = field(&DisparityMetrics::d1Est);
  result.density = field(&DisparityMetrics::density);
  for (const DisparityMetrics& m : metrics) {
    result.gtPixels += m.gtPixels;
    result.estimatedPixels += m.estimatedPixels;
  }
  return result;
}

bool sameEntry(const MethodResult& a, const MethodResult& b) {
  return a.bestAlpha == b.bestAlpha && sameMethod(a.method, b.method);
}

std::string label(const MethodResult& result) {
  if (!result.bestAlpha) return displayName(result.method);
  char text[64];
  std::snprintf(text, sizeof(text), "LiDAR-SGM (best alpha %.1f)", result.method.alpha);
  return text;
}

std::vector<MethodResult> methodMedians(const ProtocolResult& result) {
  std::vector<MethodResult> entries;
  std::vector<std::vector<DisparityMetrics>> metrics;
  std::vector<std::vector<CloudMetrics>> clouds;
  std::vector<std::vector<DepthMetrics>> depths;
  std::vector<std::vector<double>> milliseconds;
  std::vector<std::vector<ObjectSplitMetrics>> splits;
  std::vector<std::vector<ObjectSplitMetrics>> splitsOnScan;
  std::vector<std::vector<DisparityMetrics>> uncovered;
  std::vector<std::vector<CloudDistanceScore>> clouds3d;
  for (const FrameResult& frame : result.frames) {
    for (const MethodResult& method : frame.methods) {
      // The best alpha may differ between groups but is one per group: matched by role alone.
      const auto found = std::find_if(entries.begin(), entries.end(), [&method](const MethodResult& e) {
        return method.bestAlpha ? e.bestAlpha : sameEntry(e, method);
      });
      const std::size_t index = static_cast<std::size_t>(found - entries.begin());
      if (found == entries.end()) {
        entries.push_back(method);
        metrics.emplace_back();
        clouds.emplace_back();
        depths.emplace_back();
        milliseconds.emplace_back();
        splits.emplace_back();
        splitsOnScan.emplace_back();
        uncovered.emplace_back();
        clouds3d.emplace_back();
      }
      if (method.objectSplit) splits[index].push_back(*method.objectSplit);
      if (method.objectSplitOnScan) splitsOnScan[index].push_back(*method.objectSplitOnScan);
      if (method.uncovered) uncovered[index].push_back(*method.uncovered);
      if (method.cloud3d) clouds3d[index].push_back(*method.cloud3d);
      metrics[index].push_back(method.metrics);
      clouds[index].push_back(method.cloud);
      depths[index].push_back(method.depth);
      milliseconds[index].push_back(method.milliseconds);
    }
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    entries[i].metrics = medianOver(metrics[i]);
    entries[i].cloud = medianCloud(clouds[i]);
    entries[i].depth = medianDepth(depths[i]);
    entries[i].milliseconds = medianOf(milliseconds[i]);
    entries[i].numDisparities = 0;  // a range per frame, not a median
    entries[i].objectSplit.reset();
    entries[i].objectSplitFrameMean.reset();
    entries[i].objectSplitOnScan.reset();
    entries[i].uncovered.reset();
    entries[i].cloud3d.reset();
    if (!splits[i].empty()) {
      entries[i].objectSplit = pooledObjectSplit(splits[i]);
      entries[i].objectSplitFrameMean = meanObjectSplit(splits[i]);
    }
    if (!splitsOnScan[i].empty()) entries[i].objectSplitOnScan = pooledObjectSplit(splitsOnScan[i]);
    if (!uncovered[i].empty()) entries[i].uncovered = medianOver(uncovered[i]);
    if (!clouds3d[i].empty()) entries[i].cloud3d = medianCloudDistance(clouds3d[i]);
  }
  return entries;
}

std::string markdownTable(const ProtocolResult& result) {
  std::ostringstream out;
  const std::vector<MethodResult> medians = methodMedians(result);
  appendFrameTable(out, result, medians, kMetricHeader, kMetricAlignment,
                   [](const MethodResult& m) { return metricCells(m.metrics); });
  // Points within max(0.1 m, tau * z_gt) of the GT, up to 80 m; see cloud_metrics.hpp.
  out << "\nCloud: precision, completeness and F-score at tau 5 % and 3 % (points up to 80 m)\n\n";
  appendFrameTable(out, result, medians, kCloudHeader, kCloudAlignment,
                   [](const MethodResult& m) { return cloudCells(m.cloud); });
  out << "\nDepth: KITTI depth-completion metrics over GT pixels with an estimate (up to 80 m)\n\n";
  appendFrameTable(out, result, medians, kDepthHeader, kDepthAlignment,
                   [](const MethodResult& m) { return depthCells(m.depth); });
  for (const AlphaSweep& sweep : result.sweeps) appendSweepTable(out, sweep);
  return out.str();
}

nlohmann::json toJson(const std::vector<ProtocolResult>& results) {
  nlohmann::json protocols = nlohmann::json::array();
  for (const ProtocolResult& result : results) protocols.push_back(protocolJson(result));
  return {{"protocols", protocols}};
}

}  // namespace eval
}  // namespace lidar_sgm
