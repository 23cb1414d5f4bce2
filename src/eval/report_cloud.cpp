#include "report_format.hpp"
#include "report_cloud.hpp"

#include <cstdio>
#include <vector>

#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

nlohmann::json scoreJson(const CloudScore& s) {
  return {{"precision", s.precision}, {"completeness", s.completeness}, {"f_score", s.fScore}};
}

/// Median of one field over `items` (medianOf: the mean of the middle two for an even count).
template <typename T, typename Get>
double medianField(const std::vector<T>& items, Get get) {
  std::vector<double> values;
  values.reserve(items.size());
  for (const T& item : items) values.push_back(get(item));
  return medianOf(values);
}

}  // namespace

const char* const kCloudHeader =
    "precision 5 % | completeness 5 % | F 5 % | precision 3 % | completeness 3 % | F 3 %";
const char* const kCloudAlignment = "---: | ---: | ---: | ---: | ---: | ---:";
const char* const kDepthHeader = "RMSE mm | MAE mm | iRMSE 1/km | iMAE 1/km | with estimate %";
const char* const kDepthAlignment = "---: | ---: | ---: | ---: | ---:";

std::string cloudCells(const CloudMetrics& m) {
  return percent(m.tau5.precision) + " | " + percent(m.tau5.completeness) + " | " + percent(m.tau5.fScore) + " | " +
         percent(m.tau3.precision) + " | " + percent(m.tau3.completeness) + " | " + percent(m.tau3.fScore);
}

std::string depthCells(const DepthMetrics& m) {
  return fixed(m.rmseMm, 0) + " | " + fixed(m.maeMm, 0) + " | " + fixed(m.irmsePerKm, 2) + " | " +
         fixed(m.imaePerKm, 2) + " | " + percent(m.density);
}

nlohmann::json cloudJson(const CloudMetrics& m) {
  return {{"points", m.points}, {"gt_pixels", m.gtPixels}, {"tau_3", scoreJson(m.tau3)}, {"tau_5", scoreJson(m.tau5)}};
}

nlohmann::json depthJson(const DepthMetrics& m) {
  return {{"rmse_mm", m.rmseMm},       {"mae_mm", m.maeMm},       {"irmse_per_km", m.irmsePerKm},
          {"imae_per_km", m.imaePerKm}, {"density", m.density},    {"gt_pixels", m.gtPixels},
          {"estimated_pixels", m.estimatedPixels}};
}

CloudMetrics medianCloud(const std::vector<CloudMetrics>& metrics) {
  CloudMetrics result;
  if (metrics.empty()) return result;
  for (CloudScore CloudMetrics::*tau : {&CloudMetrics::tau3, &CloudMetrics::tau5}) {
    for (double CloudScore::*field : {&CloudScore::precision, &CloudScore::completeness, &CloudScore::fScore}) {
      (result.*tau).*field = medianField(metrics, [&](const CloudMetrics& m) { return (m.*tau).*field; });
    }
  }
  for (const CloudMetrics& m : metrics) {
    result.points += m.points;
    result.gtPixels += m.gtPixels;
  }
  return result;
}

DepthMetrics medianDepth(const std::vector<DepthMetrics>& metrics) {
  DepthMetrics result;
  if (metrics.empty()) return result;
  for (double DepthMetrics::*field : {&DepthMetrics::rmseMm, &DepthMetrics::maeMm, &DepthMetrics::irmsePerKm,
                                      &DepthMetrics::imaePerKm, &DepthMetrics::density}) {
    result.*field = medianField(metrics, [&](const DepthMetrics& m) { return m.*field; });
  }
  for (const DepthMetrics& m : metrics) {
    result.gtPixels += m.gtPixels;
    result.estimatedPixels += m.estimatedPixels;
  }
  return result;
}

}  // namespace eval
}  // namespace lidar_sgm
