#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "lidar_sgm/eval/confidence_curves.hpp"
#include "lidar_sgm/eval/confidence_report.hpp"

namespace lidar_sgm {
namespace {

constexpr double kFocalBaseline = 480.0;  // GT 20 px is 24 m
constexpr float kGt = 20.0f;

std::int16_t x16(double disparity) { return static_cast<std::int16_t>(std::lround(disparity * kDisparityScale)); }

/// One row of pixels: GT 20 px everywhere; a correct estimate is 20 px, a wrong one 30 px
/// (error 10 px: > 3 px and > 5 % of 20 px).
struct Row {
  std::vector<std::int16_t> estimate;
  std::vector<std::uint8_t> confidence;
  std::vector<float> groundTruth;
  std::vector<std::uint8_t> exclude;

  /// `wrong[i]`: pixel i is wrong; `conf[i]`: its confidence.
  Row(const std::vector<bool>& wrong, const std::vector<std::uint8_t>& conf)
      : confidence(conf), groundTruth(wrong.size(), kGt) {
    for (bool w : wrong) estimate.push_back(x16(w ? 30.0 : 20.0));
  }
  int width() const { return static_cast<int>(estimate.size()); }
  ImageView<const std::int16_t> e() const { return {estimate.data(), width(), 1}; }
  ImageView<const std::uint8_t> c() const { return {confidence.data(), width(), 1}; }
  ImageView<const float> g() const { return {groundTruth.data(), width(), 1}; }
  ImageView<const std::uint8_t> x() const {
    if (exclude.empty()) return {};
    return {exclude.data(), width(), 1};
  }
  eval::Sparsification sparsify(const std::vector<double>& fractions) const {
    return eval::sparsify(e(), c(), g(), x(), fractions);
  }
};

// Ten pixels, three wrong (0, 4, 7).
const std::vector<bool> kWrong{true, false, false, false, true, false, false, true, false, false};
const std::vector<double> kFractions{0.0, 0.1, 0.2, 0.3, 0.5};

std::vector<std::uint8_t> perfectConfidence() {
  std::vector<std::uint8_t> c;
  for (bool w : kWrong) c.push_back(w ? 10 : 200);
  return c;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

TEST(ConfidenceCurves, GridsAreTheIssuesOnes) {
  const std::vector<double>& t = eval::confidenceThresholds();
  ASSERT_EQ(t.size(), 11u);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t[9], 0.9);
  EXPECT_DOUBLE_EQ(t.back(), 0.95);
  const std::vector<double>& f = eval::sparsificationFractions();
  ASSERT_EQ(f.size(), 20u);
  EXPECT_DOUBLE_EQ(f.front(), 0.0);
  EXPECT_NEAR(f.back(), 0.95, 1e-12);
}

// confidence / 255 < t is dropped: t = 0.1 -> below 26 (25.5 rounded up), t = 0.5 -> below 128.
TEST(ConfidenceCurves, ThresholdsDropExactlyThePixelsBelow) {
  const std::vector<std::uint8_t> conf{0, 25, 26, 127, 128, 255};
  const std::vector<std::int16_t> estimate{16, 32, 48, 64, kInvalidDisparity, 96};
  const ImageView<const std::int16_t> e{estimate.data(), 6, 1};
  const ImageView<const std::uint8_t> c{conf.data(), 6, 1};
  const auto kept = [&](double t) {
    const Image<std::int16_t> d = eval::dropBelowConfidence(e, c, t);
    std::vector<std::int16_t> v;
    for (int x = 0; x < 6; ++x) v.push_back(d(x, 0));
    return v;
  };
  constexpr std::int16_t kNone = kInvalidDisparity;
  EXPECT_EQ(kept(0.0), estimate);  // 0 keeps every pixel, confidence 0 included
  EXPECT_EQ(kept(0.1), (std::vector<std::int16_t>{kNone, kNone, 48, 64, kNone, 96}));
  EXPECT_EQ(kept(0.5), (std::vector<std::int16_t>{kNone, kNone, kNone, kNone, kNone, 96}));
  EXPECT_EQ(kept(1.0), (std::vector<std::int16_t>{kNone, kNone, kNone, kNone, kNone, 96}));
  EXPECT_THROW(eval::dropBelowConfidence(e, c, 1.5), std::invalid_argument);
  EXPECT_THROW(eval::dropBelowConfidence(e, c, -0.1), std::invalid_argument);
  const ImageView<const std::uint8_t> shorter{conf.data(), 5, 1};
  EXPECT_THROW(eval::dropBelowConfidence(e, shorter, 0.5), std::invalid_argument);
}

// Kept 10, 9, 8, 7, 5 pixels: a confidence that puts the wrong pixels last removes them first,
// exactly as the oracle does: 3/10, 2/9, 1/8, 0, 0.
TEST(ConfidenceCurves, PerfectConfidenceMatchesTheOracle) {
  const Row row(kWrong, perfectConfidence());
  const eval::Sparsification s = row.sparsify(kFractions);
  EXPECT_EQ(s.pixels, 10);
  const std::vector<double> expected{3.0 / 10, 2.0 / 9, 1.0 / 8, 0.0, 0.0};
  ASSERT_EQ(s.error.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_DOUBLE_EQ(s.error[i], expected[i]) << "f = " << kFractions[i];
    EXPECT_DOUBLE_EQ(s.oracle[i], expected[i]) << "f = " << kFractions[i];
  }
  EXPECT_DOUBLE_EQ(s.auc, mean(expected));
  EXPECT_DOUBLE_EQ(s.auc, s.oracleAuc);
  EXPECT_DOUBLE_EQ(s.aucGap, 0.0);
}

// Every pixel tied: removing any share leaves the same share of wrong pixels (3/10), whatever the
// order of the pixels; the oracle still falls.
TEST(ConfidenceCurves, ConstantConfidenceGivesAFlatCurve) {
  const Row row(kWrong, std::vector<std::uint8_t>(10, 128));
  const eval::Sparsification s = row.sparsify(kFractions);
  for (double e : s.error) EXPECT_DOUBLE_EQ(e, 0.3);
  EXPECT_DOUBLE_EQ(s.auc, 0.3);
  EXPECT_DOUBLE_EQ(s.oracleAuc, mean({3.0 / 10, 2.0 / 9, 1.0 / 8, 0.0, 0.0}));
  EXPECT_GT(s.aucGap, 0.0);
}

// The wrong pixels most confident: the curve rises (3/10, 3/9, 3/8, 3/7, 3/5).
TEST(ConfidenceCurves, ReversedConfidenceRemovesTheCorrectPixelsFirst) {
  std::vector<std::uint8_t> reversed;
  for (bool w : kWrong) reversed.push_back(w ? 200 : 10);
  const eval::Sparsification s = Row(kWrong, reversed).sparsify(kFractions);
  const std::vector<double> expected{3.0 / 10, 3.0 / 9, 3.0 / 8, 3.0 / 7, 3.0 / 5};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_DOUBLE_EQ(s.error[i], expected[i]);
}

// Level 200: pixels 0-3, one wrong; level 100: pixels 4-9, two wrong. Keeping 5 takes level 200
// whole and one pixel of level 100 at its share 2/6: (1 + 1/3) / 5.
TEST(ConfidenceCurves, TiesAtTheCutCountWithTheirLevelsShare) {
  const std::vector<bool> wrong{true, false, false, false, true, true, false, false, false, false};
  const std::vector<std::uint8_t> conf{200, 200, 200, 200, 100, 100, 100, 100, 100, 100};
  const eval::Sparsification s = Row(wrong, conf).sparsify({0.0, 0.5, 0.6});
  EXPECT_DOUBLE_EQ(s.error[0], 0.3);
  EXPECT_DOUBLE_EQ(s.error[1], (1.0 + 1.0 / 3.0) / 5.0);
  EXPECT_DOUBLE_EQ(s.error[2], 0.25);  // exactly level 200
}

// Only pixels with an estimate, GT and not excluded are ranked; none ranked gives zeros.
TEST(ConfidenceCurves, RanksOnlyEstimatedPixelsWithGroundTruth) {
  Row row(kWrong, perfectConfidence());
  row.estimate[1] = kInvalidDisparity;
  row.groundTruth[0] = 0.0f;           // a wrong pixel without GT
  row.groundTruth[2] = std::nanf("");  // no GT either
  row.exclude.assign(10, 0);
  row.exclude[4] = 1;  // a wrong pixel that is LiDAR input
  const eval::Sparsification s = row.sparsify({0.0});
  EXPECT_EQ(s.pixels, 6);
  EXPECT_DOUBLE_EQ(s.error[0], 1.0 / 6.0);

  Row none(kWrong, perfectConfidence());
  none.groundTruth.assign(10, 0.0f);
  const eval::Sparsification empty = none.sparsify(kFractions);
  EXPECT_EQ(empty.pixels, 0);
  for (double e : empty.error) EXPECT_DOUBLE_EQ(e, 0.0);
  EXPECT_DOUBLE_EQ(empty.auc, 0.0);
}

TEST(ConfidenceCurves, RejectsBadInput) {
  const Row row(kWrong, perfectConfidence());
  EXPECT_THROW(row.sparsify({1.0}), std::invalid_argument);
  EXPECT_THROW(row.sparsify({-0.05}), std::invalid_argument);
  const std::vector<float> shorter(9, kGt);
  EXPECT_THROW(eval::sparsify(row.e(), row.c(), {shorter.data(), 9, 1}, {}, kFractions), std::invalid_argument);
}

// The cloud curve: at 0 all ten points (7 correct), at 0.5 the seven confident ones (all
// correct), at 0.9 none; completeness 7/10, 7/10, 0.
TEST(ConfidenceCurves, CloudCurveScoresTheKeptPixels) {
  const Row row(kWrong, perfectConfidence());
  const eval::ConfidenceCurves c =
      eval::confidenceCurves(row.e(), row.c(), row.g(), row.x(), kFocalBaseline, {}, {0.0, 0.5, 0.9}, kFractions);
  ASSERT_EQ(c.cloud.size(), 3u);
  EXPECT_EQ(c.cloud[0].points, 10);
  EXPECT_DOUBLE_EQ(c.cloud[0].tau5.precision, 0.7);
  EXPECT_DOUBLE_EQ(c.cloud[0].tau5.completeness, 0.7);
  EXPECT_EQ(c.cloud[1].points, 7);
  EXPECT_DOUBLE_EQ(c.cloud[1].tau5.precision, 1.0);
  EXPECT_DOUBLE_EQ(c.cloud[1].tau5.completeness, 0.7);
  EXPECT_EQ(c.cloud[2].points, 0);
  EXPECT_DOUBLE_EQ(c.cloud[2].tau5.completeness, 0.0);
  EXPECT_EQ(c.cloud[2].gtPixels, 10);
  EXPECT_EQ(c.sparsification.pixels, 10);
}

// Frames: perfect (gap 0), constant (gap > 0), reversed; and an empty curve that is skipped.
TEST(ConfidenceCurves, MediansPerFieldOverFramesWithCurves) {
  std::vector<std::uint8_t> reversed;
  for (bool w : kWrong) reversed.push_back(w ? 200 : 10);
  std::vector<eval::ConfidenceCurves> frames;
  for (const auto& conf : {perfectConfidence(), std::vector<std::uint8_t>(10, 128), reversed}) {
    const Row row(kWrong, conf);
    frames.push_back(eval::confidenceCurves(row.e(), row.c(), row.g(), row.x(), kFocalBaseline, {}, {0.0, 0.5},
                                            kFractions));
  }
  frames.emplace_back();
  const eval::ConfidenceCurves m = eval::medianCurves(frames);
  EXPECT_DOUBLE_EQ(m.sparsification.auc, 0.3);  // the constant frame's, the middle one
  EXPECT_DOUBLE_EQ(m.sparsification.aucGap, frames[1].sparsification.aucGap);
  EXPECT_DOUBLE_EQ(m.sparsification.error[4], 0.3);  // f = 0.5: 0, 0.3, 0.6
  EXPECT_EQ(m.sparsification.pixels, 30);
  EXPECT_DOUBLE_EQ(m.cloud[1].tau5.precision, 0.7);  // at 0.5: 1.0, 0.7 (all kept), 0.0 (3 wrong kept)
  EXPECT_TRUE(eval::medianCurves({eval::ConfidenceCurves{}}).empty());
  frames[0].thresholds = {0.0, 0.4};
  EXPECT_THROW(eval::medianCurves(frames), std::invalid_argument);
}

// The report keeps the methods with a confidence, in order, and says nothing without one.
TEST(ConfidenceReport, MediansPerMethodWithAConfidence) {
  const Row row(kWrong, perfectConfidence());
  eval::MethodResult fused;
  fused.method = {eval::MethodKind::FusedSgm, 0.7};
  fused.confidence = eval::confidenceCurves(row.e(), row.c(), row.g(), row.x(), kFocalBaseline);
  eval::MethodResult baseline;
  baseline.method = {eval::MethodKind::OpenCvSgbm, 0.0};
  eval::ProtocolResult result;
  result.protocol = "P3 test";
  result.frames = {{"set", "a", {baseline, fused}}, {"set", "b", {baseline, fused}}};
  const std::vector<eval::CurveMedians> medians = eval::curveMedians(result);
  ASSERT_EQ(medians.size(), 1u);
  EXPECT_EQ(medians[0].frames, 2);
  EXPECT_EQ(medians[0].entry.method.kind, eval::MethodKind::FusedSgm);
  EXPECT_NE(eval::confidenceMarkdown(result).find("| 0.00 |"), std::string::npos);  // AUC - oracle
  const nlohmann::json json = eval::confidenceJson(result);
  ASSERT_EQ(json["methods"].size(), 1u);
  EXPECT_EQ(json["methods"][0]["method"], "fused_sgm");
  EXPECT_EQ(json["methods"][0]["curve"].size(), eval::confidenceThresholds().size());
  EXPECT_DOUBLE_EQ(json["methods"][0]["sparsification"]["auc_gap"].get<double>(), 0.0);
  // The plot: two panels, drawn (not one color), written whole.
  const std::string plot = (std::filesystem::temp_directory_path() /
                            ("lidar_sgm_confidence_plot_" + std::to_string(::getpid()) + ".png")).string();
  ASSERT_TRUE(eval::writeConfidencePlot(result, plot));
  const cv::Mat picture = cv::imread(plot, cv::IMREAD_GRAYSCALE);
  std::filesystem::remove(plot);
  ASSERT_FALSE(picture.empty());
  EXPECT_GT(picture.cols, picture.rows) << "two panels side by side";
  double low = 0.0;
  double high = 0.0;
  cv::minMaxLoc(picture, &low, &high);
  EXPECT_LT(low, high);

  eval::ProtocolResult baselines;
  baselines.frames = {{"set", "a", {baseline}}};
  EXPECT_EQ(eval::confidenceMarkdown(baselines), "");
  EXPECT_TRUE(eval::confidenceJson(baselines).is_null());
  EXPECT_FALSE(eval::writeConfidencePlot(baselines, "/nonexistent/never_written.png"));
}

}  // namespace
}  // namespace lidar_sgm
