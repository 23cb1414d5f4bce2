#include "lidar_sgm/eval/cloud_distance_report.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lidar_sgm/eval/ground_truth_cloud.hpp"
#include "report_format.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

nlohmann::json orNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json bandJson(const CloudDistanceBand& band, bool withRange) {
  nlohmann::json taus = nlohmann::json::array();
  for (const CloudDistanceAtTau& s : band.scores) {
    taus.push_back({{"tau", s.tau},
                    {"precision", orNull(s.precision)},
                    {"completeness", orNull(s.completeness)},
                    {"f_score", orNull(s.fScore)},
                    {"precise_points", s.precisePoints},
                    {"covered_reference_points", s.coveredReferencePoints}});
  }
  nlohmann::json json = {{"points", band.points},
                         {"reference_points", band.referencePoints},
                         {"mean_distance", orNull(band.meanDistance)},
                         {"median_distance", orNull(band.medianDistance)},
                         {"mean_reference_distance", orNull(band.meanReferenceDistance)},
                         {"median_reference_distance", orNull(band.medianReferenceDistance)},
                         {"taus", taus}};
  if (withRange) {
    json["near"] = band.near;
    json["far"] = band.far;
  }
  return json;
}

/// A share in percent, "-" where it is not defined.
std::string share(double value, int decimals = 2) { return std::isnan(value) ? "-" : percent(value, decimals); }
std::string metres(double value, int decimals) { return std::isnan(value) ? "-" : fixed(value, decimals); }

std::string bandName(const CloudDistanceBand& band) { return fixed(band.near, 0) + "-" + fixed(band.far, 0) + " m"; }

/// The median of `values` with the NaNs left out; NaN when none is left.
double medianDefined(const std::vector<double>& values) {
  std::vector<double> defined;
  for (double v : values) {
    if (!std::isnan(v)) defined.push_back(v);
  }
  return defined.empty() ? kUndefined : medianOf(defined);
}

CloudDistanceBand medianBand(const std::vector<const CloudDistanceBand*>& bands) {
  CloudDistanceBand result = *bands.front();
  const auto field = [&bands](auto get) {
    std::vector<double> values;
    for (const CloudDistanceBand* b : bands) values.push_back(get(*b));
    return medianDefined(values);
  };
  result.points = 0;
  result.referencePoints = 0;
  for (const CloudDistanceBand* b : bands) {
    if (b->scores.size() != result.scores.size() || b->near != result.near || b->far != result.far) {
      throw std::invalid_argument("medianCloudDistance: the scores differ in their taus or bands");
    }
    result.points += b->points;
    result.referencePoints += b->referencePoints;
  }
  result.meanDistance = field([](const CloudDistanceBand& b) { return b.meanDistance; });
  result.medianDistance = field([](const CloudDistanceBand& b) { return b.medianDistance; });
  result.meanReferenceDistance = field([](const CloudDistanceBand& b) { return b.meanReferenceDistance; });
  result.medianReferenceDistance = field([](const CloudDistanceBand& b) { return b.medianReferenceDistance; });
  for (std::size_t t = 0; t < result.scores.size(); ++t) {
    CloudDistanceAtTau& s = result.scores[t];
    for (const CloudDistanceBand* b : bands) {
      if (b->scores[t].tau != s.tau) throw std::invalid_argument("medianCloudDistance: the scores differ in their taus");
    }
    s.precisePoints = 0;
    s.coveredReferencePoints = 0;
    for (const CloudDistanceBand* b : bands) {
      s.precisePoints += b->scores[t].precisePoints;
      s.coveredReferencePoints += b->scores[t].coveredReferencePoints;
    }
    s.precision = field([t](const CloudDistanceBand& b) { return b.scores[t].precision; });
    s.completeness = field([t](const CloudDistanceBand& b) { return b.scores[t].completeness; });
    s.fScore = field([t](const CloudDistanceBand& b) { return b.scores[t].fScore; });
  }
  return result;
}

/// The index of `tau` among the score's taus, or -1.
int tauIndex(const CloudDistanceBand& band, double tau) {
  for (std::size_t t = 0; t < band.scores.size(); ++t) {
    if (std::abs(band.scores[t].tau - tau) < 1e-12) return static_cast<int>(t);
  }
  return -1;
}

}  // namespace

nlohmann::json cloudDistanceJson(const CloudDistanceScore& score) {
  nlohmann::json bands = nlohmann::json::array();
  for (const CloudDistanceBand& band : score.bands) bands.push_back(bandJson(band, true));
  return {{"points", score.overall.points},
          {"reference_points", score.overall.referencePoints},
          {"skipped_points", score.skippedPoints},
          {"skipped_reference_points", score.skippedReferencePoints},
          {"unjudged_points", score.unjudgedPoints},
          {"overall", bandJson(score.overall, false)},
          {"bands", bands}};
}

std::string cloudDistanceText(const CloudDistanceScore& score) {
  std::vector<std::pair<std::string, const CloudDistanceBand*>> rows{{"all", &score.overall}};
  for (const CloudDistanceBand& band : score.bands) rows.emplace_back(bandName(band), &band);
  std::ostringstream out;
  char line[200];
  for (std::size_t t = 0; t < score.overall.scores.size(); ++t) {
    std::snprintf(line, sizeof(line), "tau %g m\n  %-12s %10s %10s %10s %13s %9s\n", score.overall.scores[t].tau,
                  "range", "points", "reference", "precision", "completeness", "F-score");
    out << line;
    for (const auto& [name, band] : rows) {
      const CloudDistanceAtTau& s = band->scores[t];
      std::snprintf(line, sizeof(line), "  %-12s %10ld %10ld %8s %% %11s %% %7s %%\n", name.c_str(), band->points,
                    band->referencePoints, share(s.precision).c_str(), share(s.completeness).c_str(),
                    share(s.fScore).c_str());
      out << line;
    }
  }
  std::snprintf(line, sizeof(line), "nearest-neighbour distance [m]\n  %-12s %14s %10s %14s %10s\n", "range",
                "cloud->ref mean", "median", "ref->cloud mean", "median");
  out << line;
  for (const auto& [name, band] : rows) {
    std::snprintf(line, sizeof(line), "  %-12s %14s %10s %14s %10s\n", name.c_str(),
                  metres(band->meanDistance, 4).c_str(), metres(band->medianDistance, 4).c_str(),
                  metres(band->meanReferenceDistance, 4).c_str(), metres(band->medianReferenceDistance, 4).c_str());
    out << line;
  }
  if (score.skippedPoints > 0 || score.skippedReferencePoints > 0) {
    std::snprintf(line, sizeof(line), "skipped (NaN or infinite): %ld cloud points, %ld reference points\n",
                  score.skippedPoints, score.skippedReferencePoints);
    out << line;
  }
  return out.str();
}

CloudDistanceScore medianCloudDistance(const std::vector<CloudDistanceScore>& scores) {
  CloudDistanceScore result;
  if (scores.empty()) return result;
  std::vector<const CloudDistanceBand*> overall;
  for (const CloudDistanceScore& s : scores) {
    if (s.bands.size() != scores.front().bands.size()) {
      throw std::invalid_argument("medianCloudDistance: the scores differ in their bands");
    }
    overall.push_back(&s.overall);
    result.skippedPoints += s.skippedPoints;
    result.skippedReferencePoints += s.skippedReferencePoints;
    result.unjudgedPoints += s.unjudgedPoints;
  }
  result.overall = medianBand(overall);
  for (std::size_t b = 0; b < scores.front().bands.size(); ++b) {
    std::vector<const CloudDistanceBand*> band;
    for (const CloudDistanceScore& s : scores) band.push_back(&s.bands[b]);
    result.bands.push_back(medianBand(band));
  }
  return result;
}

std::string groundTruthCloudMarkdown(const ProtocolResult& result) {
  const std::vector<MethodResult> medians = methodMedians(result);
  const CloudDistanceScore* first = nullptr;
  for (const MethodResult& m : medians) {
    if (m.cloud3d && !first) first = &*m.cloud3d;
  }
  if (!first) return {};
  const int t = tauIndex(first->overall, kGroundTruthCloudTau);
  if (t < 0) return {};
  std::ostringstream out;
  out << "\n3D: each method's cloud against the GT's cloud (both reprojected into the left camera, up to 80 m; "
         "precision over the points of GT pixels), tau "
      << fixed(kGroundTruthCloudTau, 1) << " m, median over the frames; F per range band from the camera\n\n"
      << "| method | precision % | completeness % | F % |";
  for (const CloudDistanceBand& band : first->bands) out << " F " << bandName(band) << " |";
  out << " median distance cm |\n| --- | ---: | ---: | ---: |";
  for (std::size_t b = 0; b < first->bands.size(); ++b) out << " ---: |";
  out << " ---: |\n";
  for (const MethodResult& m : medians) {
    if (!m.cloud3d) continue;
    const CloudDistanceScore& s = *m.cloud3d;
    const CloudDistanceAtTau& all = s.overall.scores[static_cast<std::size_t>(t)];
    out << "| " << label(m) << " | " << share(all.precision) << " | " << share(all.completeness) << " | "
        << share(all.fScore) << " |";
    for (const CloudDistanceBand& band : s.bands) out << " " << share(band.scores[static_cast<std::size_t>(t)].fScore) << " |";
    out << " " << metres(100.0 * s.overall.medianDistance, 1) << " |\n";
  }
  return out.str();
}

}  // namespace eval
}  // namespace lidar_sgm
