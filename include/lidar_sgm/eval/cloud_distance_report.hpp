#pragma once
/// @file cloud_distance_report.hpp  The 3D cloud-to-cloud scores (cloud_distance.hpp) written out:
/// JSON, a terminal table, medians over frames and the KITTI142 table.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lidar_sgm/eval/cloud_distance.hpp"
#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {

/// {"points","reference_points","skipped_points","skipped_reference_points","unjudged_points",
/// "overall":BAND,"bands":[BAND...]}, BAND = {["near","far",] "points","reference_points",
/// "mean_distance","median_distance","mean_reference_distance","median_reference_distance",
/// "taus":[{"tau","precision","completeness","f_score","precise_points","covered_reference_points"}]}
/// in metres and fractions in [0, 1]; "not defined" (NaN) is null. "near"/"far" only in bands.
nlohmann::json cloudDistanceJson(const CloudDistanceScore& score);

/// For the terminal: per tau, a row for every point and one per band (points, reference points,
/// precision, completeness, F-score), then the nearest-neighbour distances per band.
std::string cloudDistanceText(const CloudDistanceScore& score);

/// Per-field medians over frames of the shares and distances, frames where a figure is not
/// defined (NaN) left out of its median; counts summed. The scores must share their taus and
/// bands (one protocol's); std::invalid_argument otherwise. Empty input gives an empty score.
CloudDistanceScore medianCloudDistance(const std::vector<CloudDistanceScore>& scores);

/// The KITTI142 table beside the paper's: per method (medians over the frames, methodMedians)
/// precision, completeness and F at kGroundTruthCloudTau overall, F per range band and the median
/// distance of the points to the GT's cloud. Empty when no method has 3D scores.
std::string groundTruthCloudMarkdown(const ProtocolResult& result);

}  // namespace eval
}  // namespace lidar_sgm
