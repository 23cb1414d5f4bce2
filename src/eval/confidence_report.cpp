#include "report_format.hpp"
#include "lidar_sgm/eval/confidence_report.hpp"

#include <cstdio>

#include <opencv2/core.hpp>

#include "lidar_sgm/io/image_io.hpp"
#include "plots.hpp"
#include "report_cloud.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

/// The colours of the alpha-sweep and reliability plots (matplotlib's first four), BGR.
cv::Scalar colorOf(std::size_t i) {
  static const cv::Scalar colors[] = {cv::Scalar(180, 119, 31), cv::Scalar(14, 127, 255), cv::Scalar(44, 160, 44),
                                      cv::Scalar(40, 39, 214), cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140)};
  return colors[i % (sizeof(colors) / sizeof(colors[0]))];
}

/// Half way to white: the oracle beside its method.
cv::Scalar lighter(const cv::Scalar& c) { return (c + cv::Scalar(255, 255, 255)) * 0.5; }

}  // namespace

std::vector<CurveMedians> curveMedians(const ProtocolResult& result) {
  std::vector<CurveMedians> medians;
  std::vector<std::vector<ConfidenceCurves>> perFrame;
  for (const FrameResult& frame : result.frames) {
    for (const MethodResult& m : frame.methods) {
      if (m.confidence.empty()) continue;
      std::size_t i = 0;
      while (i < medians.size() && !sameEntry(medians[i].entry, m)) ++i;
      if (i == medians.size()) {
        medians.push_back({m, {}, 0});
        perFrame.emplace_back();
      }
      perFrame[i].push_back(m.confidence);
      ++medians[i].frames;
    }
  }
  for (std::size_t i = 0; i < medians.size(); ++i) medians[i].median = medianCurves(perFrame[i]);
  return medians;
}

std::string confidenceMarkdown(const ProtocolResult& result) {
  const std::vector<CurveMedians> medians = curveMedians(result);
  if (medians.empty()) return "";
  const std::vector<double>& thresholds = medians.front().median.thresholds;
  std::string md = "Confidence curve: precision / completeness [%] at tau 5 % after dropping the pixels below each "
                   "minimum confidence (medians over the frames).\n\n| method |";
  std::string alignment = "| --- |";
  for (double t : thresholds) {
    md += " >= " + fixed(t, t == 0.95 ? 2 : 1) + " |";
    alignment += " ---: |";
  }
  md += "\n" + alignment + "\n";
  for (const CurveMedians& m : medians) {
    md += "| " + label(m.entry) + " |";
    for (const CloudMetrics& c : m.median.cloud) {
      md += " " + percent(c.tau5.precision, 1) + " / " + percent(c.tau5.completeness, 1) + " |";
    }
    md += "\n";
  }
  md += "\nSparsification (shares of wrong pixels, KITTI's > 3 px and > 5 %, among the ranked pixels; medians over "
        "the frames):\n\n| method | frames | ranked pixels | error at f = 0 % | AUC % | oracle AUC % | AUC - oracle % "
        "|\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const CurveMedians& m : medians) {
    const Sparsification& s = m.median.sparsification;
    md += "| " + label(m.entry) + " | " + std::to_string(m.frames) + " | " + std::to_string(s.pixels) + " | " +
          percent(s.error.empty() ? 0.0 : s.error.front()) + " | " + percent(s.auc) + " | " + percent(s.oracleAuc) +
          " | " + percent(s.aucGap) + " |\n";
  }
  return md;
}

nlohmann::json confidenceJson(const ProtocolResult& result) {
  const std::vector<CurveMedians> medians = curveMedians(result);
  if (medians.empty()) return nullptr;
  nlohmann::json methods = nlohmann::json::array();
  for (const CurveMedians& m : medians) {
    nlohmann::json entry;
    entry["method"] = methodId(m.entry.method.kind);
    if (m.entry.method.usesAlpha()) entry["alpha"] = m.entry.method.alpha;
    entry["name"] = label(m.entry);
    entry["frames"] = m.frames;
    nlohmann::json curve = nlohmann::json::array();
    for (std::size_t t = 0; t < m.median.thresholds.size(); ++t) {
      curve.push_back({{"min_confidence", m.median.thresholds[t]}, {"cloud", cloudJson(m.median.cloud[t])}});
    }
    entry["curve"] = curve;
    const Sparsification& s = m.median.sparsification;
    entry["sparsification"] = {{"error", s.error}, {"oracle", s.oracle},        {"auc", s.auc},
                               {"oracle_auc", s.oracleAuc}, {"auc_gap", s.aucGap}, {"pixels", s.pixels}};
    methods.push_back(entry);
  }
  return {{"thresholds", medians.front().median.thresholds},
          {"fractions", medians.front().median.sparsification.fractions},
          {"methods", methods}};
}

bool writeConfidencePlot(const ProtocolResult& result, const std::string& path) {
  const std::vector<CurveMedians> medians = curveMedians(result);
  if (medians.empty()) return false;
  PlotSpec curve;
  curve.title = result.protocol + ": precision vs completeness (tau 5 %)";
  curve.xLabel = "completeness [%]";
  curve.yLabel = "precision [%]";
  PlotSpec sparsification;
  sparsification.title = result.protocol + ": sparsification";
  sparsification.xLabel = "fraction removed (least confident first)";
  sparsification.yLabel = "wrong pixels among the rest [%]";
  for (std::size_t i = 0; i < medians.size(); ++i) {
    const ConfidenceCurves& c = medians[i].median;
    PlotSeries line{label(medians[i].entry), {}, {}, colorOf(i), {}};
    for (std::size_t t = 0; t < c.thresholds.size(); ++t) {
      line.x.push_back(100.0 * c.cloud[t].tau5.completeness);
      line.y.push_back(100.0 * c.cloud[t].tau5.precision);
      // A few labels only: eleven per line would hide the lines.
      const double th = c.thresholds[t];
      const bool fused = medians[i].entry.method.kind == MethodKind::FusedSgm;
      const bool labelled = fused && (th == 0.0 || th == 0.5 || th == 0.9);
      line.labels.push_back(labelled ? fixed(th, 1) : "");
    }
    curve.series.push_back(line);
    PlotSeries error{label(medians[i].entry), {}, {}, colorOf(i), {}};
    const std::string oracleName = std::string("oracle of ") + methodId(medians[i].entry.method.kind);
    PlotSeries oracle{oracleName, {}, {}, lighter(colorOf(i)), {}};
    for (std::size_t f = 0; f < c.sparsification.fractions.size(); ++f) {
      error.x.push_back(c.sparsification.fractions[f]);
      error.y.push_back(100.0 * c.sparsification.error[f]);
      oracle.x.push_back(c.sparsification.fractions[f]);
      oracle.y.push_back(100.0 * c.sparsification.oracle[f]);
    }
    sparsification.series.push_back(error);
    sparsification.series.push_back(oracle);
  }
  io::writeImageAtomically(path, hconcat({linePlot(curve), linePlot(sparsification)}));
  return true;
}

}  // namespace eval
}  // namespace lidar_sgm
