#pragma once
// The cloud and depth metrics' part of the report (report.cpp): their Markdown cells and JSON, so
// that report.cpp lays out tables and does not need to know each metric.

#include <string>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/cloud_metrics.hpp"

namespace lidar_sgm {
namespace eval {

extern const char* const kCloudHeader;     ///< "precision 5 % | ... | F 3 %"
extern const char* const kCloudAlignment;  ///< "---: | ..." for as many columns
extern const char* const kDepthHeader;     ///< "RMSE mm | MAE mm | iRMSE 1/km | iMAE 1/km | with estimate %"
extern const char* const kDepthAlignment;

/// Precision, completeness, F at tau 5 % then 3 %, in percent with 2 decimals.
std::string cloudCells(const CloudMetrics& m);

/// RMSE and MAE [mm] with 0 decimals (KITTI's own precision), iRMSE and iMAE [1/km] with 2, share
/// of GT pixels with an estimate in percent with 2.
std::string depthCells(const DepthMetrics& m);

nlohmann::json cloudJson(const CloudMetrics& m);
nlohmann::json depthJson(const DepthMetrics& m);

}  // namespace eval
}  // namespace lidar_sgm
