#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "lidar_sgm/eval/report.hpp"

namespace lidar_sgm {
namespace eval {
namespace {
namespace fs = std::filesystem;

DisparityMetrics metrics(double correct, double rmse, double d1, double density, long gtPixels = 100) {
  DisparityMetrics m;
  m.correct = correct;
  m.rmse = rmse;
  m.d1 = d1;
  m.d1Est = d1 / 2;
  m.density = density;
  m.gtPixels = gtPixels;
  m.estimatedPixels = gtPixels / 2;
  return m;
}

TEST(MedianOver, OddAndEvenCounts) {
  const DisparityMetrics odd = medianOver({metrics(0.1, 1, 0.1, 0.1), metrics(0.3, 3, 0.3, 0.3), metrics(0.2, 2, 0.2, 0.2)});
  EXPECT_DOUBLE_EQ(odd.correct, 0.2);
  EXPECT_DOUBLE_EQ(odd.rmse, 2.0);
  EXPECT_DOUBLE_EQ(odd.d1, 0.2);
  EXPECT_DOUBLE_EQ(odd.d1Est, 0.1);
  EXPECT_DOUBLE_EQ(odd.density, 0.2);
  EXPECT_EQ(odd.gtPixels, 300);  // counts are summed
  EXPECT_EQ(odd.estimatedPixels, 150);

  const DisparityMetrics even =
      medianOver({metrics(1, 1, 1, 1), metrics(2, 2, 2, 2), metrics(3, 3, 3, 3), metrics(4, 4, 4, 4)});
  EXPECT_DOUBLE_EQ(even.correct, 2.5);  // mean of the two middle values
  EXPECT_DOUBLE_EQ(even.rmse, 2.5);
  EXPECT_DOUBLE_EQ(medianOf({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(medianOf({1, 3, 2}), 2.0);
  EXPECT_EQ(medianOver({}).gtPixels, 0);
}

CloudMetrics cloud(double precision5, double completeness5, double f5) {
  CloudMetrics m;
  m.points = 10;
  m.gtPixels = 20;
  m.tau5 = {precision5, completeness5, f5};
  m.tau3 = {precision5 / 2, completeness5 / 2, f5 / 2};
  return m;
}

DepthMetrics depth(double rmseMm, double maeMm, double irmsePerKm, double imaePerKm, double density) {
  DepthMetrics m;
  m.rmseMm = rmseMm;
  m.maeMm = maeMm;
  m.irmsePerKm = irmsePerKm;
  m.imaePerKm = imaePerKm;
  m.density = density;
  m.gtPixels = 30;
  m.estimatedPixels = 15;
  return m;
}

TEST(MedianCloudAndDepth, PerFieldMediansAndSummedCounts) {
  const CloudMetrics c = medianCloud({cloud(0.9, 0.5, 0.6), cloud(0.7, 0.8, 0.75), cloud(0.8, 0.6, 0.7)});
  EXPECT_DOUBLE_EQ(c.tau5.precision, 0.8);
  EXPECT_DOUBLE_EQ(c.tau5.completeness, 0.6);
  EXPECT_DOUBLE_EQ(c.tau5.fScore, 0.7);  // the median F, not the F of the medians
  EXPECT_DOUBLE_EQ(c.tau3.precision, 0.4);
  EXPECT_EQ(c.points, 30);
  EXPECT_EQ(c.gtPixels, 60);
  const DepthMetrics d = medianDepth({depth(1000, 300, 3, 1, 0.9), depth(2000, 100, 5, 2, 0.5)});
  EXPECT_DOUBLE_EQ(d.rmseMm, 1500.0);
  EXPECT_DOUBLE_EQ(d.maeMm, 200.0);
  EXPECT_DOUBLE_EQ(d.irmsePerKm, 4.0);
  EXPECT_DOUBLE_EQ(d.imaePerKm, 1.5);
  EXPECT_DOUBLE_EQ(d.density, 0.7);
  EXPECT_EQ(d.estimatedPixels, 30);
  EXPECT_EQ(medianCloud({}).points, 0);
  EXPECT_EQ(medianDepth({}).gtPixels, 0);
}

/// Two frames x two methods, and one sweep.
ProtocolResult tinyProtocol() {
  ProtocolResult p;
  p.protocol = "P1";
  p.description = "KITTI 2015, LiDAR pixels excluded";
  const Method fused{MethodKind::FusedSgm, 0.7};
  const Method sgbm{MethodKind::OpenCvSgbm, 0.0};
  p.frames.push_back({"kitti2015", "000000",
                      {{fused, metrics(0.96123, 0.81234, 0.021, 0.98765), 12.5},
                       {sgbm, metrics(0.80, 1.25, 0.15, 0.90), 30.0}}});
  p.frames.push_back({"kitti2015", "000001",
                      {{fused, metrics(0.94, 0.7, 0.03, 0.99), 13.5},
                       {sgbm, metrics(0.82, 1.35, 0.13, 0.92), 31.0}}});
  p.sweeps.push_back({MethodKind::FusedSgm, {{0.0, metrics(0.9, 1.0, 0.05, 0.97)}, {0.5, metrics(0.95, 0.8, 0.03, 0.98)}}});
  p.frames[0].methods[0].cloud = cloud(0.95, 0.9, 0.92439);
  p.frames[0].methods[0].depth = depth(1288.4, 302.6, 3.456, 1.2, 0.97);
  p.frames[1].methods[0].cloud = cloud(0.97, 0.8, 0.87684);
  p.frames[1].methods[0].depth = depth(1000, 200, 2, 1, 0.95);
  return p;
}

TEST(MarkdownTable, RowsPerFrameAndMethodThenMedians) {
  const std::string table = markdownTable(tinyProtocol());
  EXPECT_NE(table.find("| frame | method | correct % | RMSE px | D1 % | density % |"), std::string::npos) << table;
  // Tables are for people: display names.
  EXPECT_NE(table.find("| kitti2015/000000 | LiDAR-SGM (alpha 0.7) | 96.12 | 0.812 | 2.10 | 98.77 |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| kitti2015/000001 | OpenCV StereoSGBM | 82.00 | 1.350 | 13.00 | 92.00 |"), std::string::npos)
      << table;
  // Medians of two frames: mean of both.
  EXPECT_NE(table.find("| median | LiDAR-SGM (alpha 0.7) | 95.06 | 0.756 | 2.55 | 98.88 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| median | OpenCV StereoSGBM | 81.00 | 1.300 | 14.00 | 91.00 |"), std::string::npos) << table;
  EXPECT_LT(table.find("| kitti2015/000001 |"), table.find("| median |"));  // medians come last
  EXPECT_NE(table.find("| 0.50 | 95.00 | 0.800 | 3.00 | 98.00 |"), std::string::npos) << table;  // the sweep
}

TEST(MarkdownTable, CloudAndDepthTablesBetweenTheFramesAndTheSweep) {
  const std::string table = markdownTable(tinyProtocol());
  const std::size_t cloudHeader = table.find(
      "| frame | method | precision 5 % | completeness 5 % | F 5 % | precision 3 % | completeness 3 % | F 3 % |");
  const std::size_t depthHeader =
      table.find("| frame | method | RMSE mm | MAE mm | iRMSE 1/km | iMAE 1/km | with estimate % |");
  ASSERT_NE(cloudHeader, std::string::npos) << table;
  ASSERT_NE(depthHeader, std::string::npos) << table;
  EXPECT_LT(table.find("| median | OpenCV StereoSGBM | 81.00 |"), cloudHeader);  // the disparity table first
  EXPECT_LT(cloudHeader, depthHeader);
  EXPECT_LT(depthHeader, table.find("| 0.50 |"));  // the sweep last
  EXPECT_NE(table.find("| kitti2015/000000 | LiDAR-SGM (alpha 0.7) | 95.00 | 90.00 | 92.44 | 47.50 | 45.00 | 46.22 |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| kitti2015/000000 | LiDAR-SGM (alpha 0.7) | 1288 | 303 | 3.46 | 1.20 | 97.00 |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| median | LiDAR-SGM (alpha 0.7) | 96.00 | 85.00 | 90.06 |"), std::string::npos) << table;
  EXPECT_NE(table.find("| median | LiDAR-SGM (alpha 0.7) | 1144 | 251 | 2.73 | 1.10 | 96.00 |"), std::string::npos)
      << table;
}

TEST(ToJson, RoundTripsEveryFigure) {
  const std::string text = toJson({tinyProtocol()}).dump(2);
  const nlohmann::json parsed = nlohmann::json::parse(text);
  const nlohmann::json& p1 = parsed.at("protocols").at(0);
  EXPECT_EQ(p1.at("protocol"), "P1");
  const nlohmann::json& fused = p1.at("frames").at(0).at("methods").at(0);
  // Machines read the stable id and the alpha, never the display name.
  EXPECT_EQ(fused.at("method"), "fused_sgm");
  EXPECT_DOUBLE_EQ(fused.at("alpha").get<double>(), 0.7);
  EXPECT_EQ(fused.at("best_alpha"), false);
  EXPECT_EQ(fused.at("name"), "LiDAR-SGM (alpha 0.7)");
  const nlohmann::json& sgbm = p1.at("frames").at(0).at("methods").at(1);
  EXPECT_EQ(sgbm.at("method"), "opencv_sgbm");
  EXPECT_FALSE(sgbm.contains("alpha"));  // SGBM has no LiDAR weight
  EXPECT_DOUBLE_EQ(fused.at("correct").get<double>(), 0.96123);
  EXPECT_DOUBLE_EQ(fused.at("d1_est").get<double>(), 0.0105);
  EXPECT_EQ(fused.at("gt_pixels").get<long>(), 100);
  EXPECT_DOUBLE_EQ(fused.at("ms").get<double>(), 12.5);
  ASSERT_EQ(p1.at("medians").size(), 2u);
  EXPECT_EQ(p1.at("medians").at(0).at("method"), "fused_sgm");
  EXPECT_DOUBLE_EQ(p1.at("medians").at(0).at("ms").get<double>(), 13.0);
  EXPECT_EQ(p1.at("medians").at(1).at("method"), "opencv_sgbm");
  EXPECT_DOUBLE_EQ(p1.at("medians").at(1).at("rmse").get<double>(), 1.3);
  EXPECT_EQ(p1.at("medians").at(1).at("gt_pixels").get<long>(), 200);
  EXPECT_DOUBLE_EQ(p1.at("sweeps").at("fused_sgm").at(1).at("alpha").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(p1.at("sweeps").at("fused_sgm").at(1).at("correct").get<double>(), 0.95);
  const nlohmann::json& c = fused.at("cloud");
  EXPECT_DOUBLE_EQ(c.at("tau_5").at("precision").get<double>(), 0.95);
  EXPECT_DOUBLE_EQ(c.at("tau_5").at("completeness").get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(c.at("tau_5").at("f_score").get<double>(), 0.92439);
  EXPECT_DOUBLE_EQ(c.at("tau_3").at("precision").get<double>(), 0.475);
  EXPECT_EQ(c.at("points").get<long>(), 10);
  const nlohmann::json& d = fused.at("depth");
  EXPECT_DOUBLE_EQ(d.at("rmse_mm").get<double>(), 1288.4);
  EXPECT_DOUBLE_EQ(d.at("mae_mm").get<double>(), 302.6);
  EXPECT_DOUBLE_EQ(d.at("irmse_per_km").get<double>(), 3.456);
  EXPECT_DOUBLE_EQ(d.at("imae_per_km").get<double>(), 1.2);
  EXPECT_DOUBLE_EQ(d.at("density").get<double>(), 0.97);
  EXPECT_EQ(d.at("estimated_pixels").get<long>(), 15);
  EXPECT_DOUBLE_EQ(p1.at("medians").at(0).at("depth").at("rmse_mm").get<double>(), 1144.2);
  EXPECT_DOUBLE_EQ(p1.at("medians").at(0).at("cloud").at("tau_5").at("precision").get<double>(), 0.96);
}

TEST(MethodMedians, KeepsAlphasAndTheSweepsBestApart) {
  // The same kind at two alphas, and the sweep's best at the paper's alpha: three entries.
  ProtocolResult p;
  MethodResult best{{MethodKind::FusedSgm, 0.7}, metrics(0.99, 0.5, 0.01, 1.0), 0.0};
  best.bestAlpha = true;
  for (const char* frame : {"a", "b"}) {
    p.frames.push_back({"d", frame,
                        {{{MethodKind::FusedSgm, 0.7}, metrics(0.9, 1, 0.1, 1), 1.0},
                         {{MethodKind::FusedSgm, 0.5}, metrics(0.8, 1, 0.2, 1), 1.0},
                         best}});
  }
  const std::vector<MethodResult> medians = methodMedians(p);
  ASSERT_EQ(medians.size(), 3u);
  EXPECT_DOUBLE_EQ(medians[0].metrics.correct, 0.9);
  EXPECT_DOUBLE_EQ(medians[1].metrics.correct, 0.8);
  EXPECT_TRUE(medians[2].bestAlpha);
  EXPECT_EQ(label(medians[2]), "LiDAR-SGM (best alpha 0.7)");
  EXPECT_EQ(medians[2].metrics.gtPixels, 200);
}

// Table II over frames as KITTI's devkit summarises it: the counts summed, then the shares. A frame
// with one object pixel, wrong, and one with 99, right: the pooled foreground error is 1 %, the
// mean of the frames' shares 50 %.
TEST(MethodMedians, TableTwoSumsTheFramesCountsAsKittisDevkitAndKeepsTheFrameMeanApart) {
  ObjectSplitMetrics small;
  small.gtPixels = 10;
  small.foregroundPixels = 1;
  small.estimatedBackground = 9;
  small.estimatedForeground = 1;
  small.wrongForeground = 1;
  ObjectSplitMetrics large;
  large.gtPixels = 200;
  large.foregroundPixels = 99;
  large.estimatedBackground = 100;
  large.estimatedForeground = 99;
  large.wrongBackground = 2;
  ProtocolResult p;
  for (const ObjectSplitMetrics& counts : {small, large}) {
    MethodResult fused{{MethodKind::FusedSgm, 0.7}, metrics(0.9, 1, 0.1, 1), 1.0};
    fused.objectSplit = withShares(counts);
    p.frames.push_back({"d", counts.gtPixels == 10 ? "small" : "large", {fused}});
  }
  EXPECT_DOUBLE_EQ(p.frames[0].methods[0].objectSplit->foreground, 1.0);
  const std::vector<MethodResult> medians = methodMedians(p);
  ASSERT_EQ(medians.size(), 1u);
  ASSERT_TRUE(medians[0].objectSplit && medians[0].objectSplitFrameMean);
  const ObjectSplitMetrics& pooled = *medians[0].objectSplit;
  EXPECT_DOUBLE_EQ(pooled.foreground, 1.0 / 100.0);
  EXPECT_DOUBLE_EQ(pooled.background, 2.0 / 109.0);
  EXPECT_DOUBLE_EQ(pooled.total, 3.0 / 209.0);
  EXPECT_DOUBLE_EQ(pooled.density, 209.0 / 210.0);
  EXPECT_EQ(pooled.wrongForeground, 1);
  EXPECT_EQ(pooled.gtPixels, 210);
  const ObjectSplitMetrics& mean = *medians[0].objectSplitFrameMean;
  EXPECT_DOUBLE_EQ(mean.foreground, (1.0 + 0.0) / 2.0);
  EXPECT_DOUBLE_EQ(mean.total, (1.0 / 10.0 + 2.0 / 199.0) / 2.0);
  EXPECT_DOUBLE_EQ(mean.density, (1.0 + 199.0 / 200.0) / 2.0);
  // Both on the paper's Table II: the pooled shares first, the frame mean in the last columns.
  const std::string tables = paperTablesMarkdown(p);
  EXPECT_NE(tables.find("as KITTI's devkit counts them"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| LiDAR-SGM (alpha 0.7) | 1.83 | 1.00 | 1.44 | 99.52 | 50.00 | 5.50 |"), std::string::npos)
      << tables;
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
