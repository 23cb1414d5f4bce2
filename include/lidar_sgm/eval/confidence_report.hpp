#pragma once
/// @file confidence_report.hpp  The confidence curves of a group (confidence_curves.hpp) as the
/// report shows them: medians over the frames per method, a Markdown section, a JSON object and
/// a plot.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/confidence_curves.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {

/// One method's curves over a group's frames.
struct CurveMedians {
  MethodResult entry;       ///< the method (as in methodMedians; its metrics are not used here)
  ConfidenceCurves median;  ///< medianCurves over the frames
  int frames = 0;           ///< frames with curves
};

/// Per method entry with a confidence (sameEntry; in order of first appearance) its medians over
/// the frames; methods without one (the baselines) are left out.
std::vector<CurveMedians> curveMedians(const ProtocolResult& result);

/// Markdown: a "confidence curve" table (method | one column per minimum confidence with
/// "precision / completeness" at tau 5 % in percent) and a "sparsification" table (method |
/// ranked pixels | error at f = 0 | AUC | oracle AUC | AUC - oracle, in percent). Empty when no
/// method has a confidence.
std::string confidenceMarkdown(const ProtocolResult& result);

/// {"thresholds":[...],"fractions":[...],"methods":[{"method",["alpha",]"name","frames",
/// "curve":[{"min_confidence","cloud":{as report.hpp's "cloud"}}],"sparsification":{"error":[...],
/// "oracle":[...],"auc","oracle_auc","auc_gap","pixels"}}]}; shares as fractions. Null when no
/// method has a confidence.
nlohmann::json confidenceJson(const ProtocolResult& result);

/// Two panels side by side: precision vs completeness at tau 5 % (one line per method, a marker
/// per minimum confidence, some labelled) and the sparsification curves (each method and its
/// oracle). Returns false, writing nothing, when no method has a confidence.
bool writeConfidencePlot(const ProtocolResult& result, const std::string& path);

}  // namespace eval
}  // namespace lidar_sgm
