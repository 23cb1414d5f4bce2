// Fitting and checking the confidence models (core/confidence.hpp) on synthetic frames with exact GT.
#include "lidar_sgm/eval/confidence_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/eval/report.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "plots.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

constexpr int kFeatures = 13;  // in the order of ConfidenceModel

std::array<double, kFeatures> featuresOf(const ConfidencePixel& p) {
  const bool noCounterpart = p.leftRight == kNoCounterpartDifference;
  const int r = noCounterpart ? 0 : std::min(p.leftRight, kLeftRightDifferenceCap);
  return {1.0,
          double(p.margin),
          double(std::min(p.margin, 16)),
          double(p.cost),
          double(r),
          noCounterpart ? 1.0 : 0.0,
          double(p.lidarDistance),
          double(std::min(p.lidarDistance, 4)),
          double(p.texture),
          double(std::min(p.texture, 8)),
          double(p.saturated),
          double(p.disparityRange),
          double(std::min(p.disparityRange, 2))};
}

std::uint8_t confidenceOf(const ConfidenceModel& model, const ConfidencePixel& p) {
  return confidenceFromLogit256(confidenceLogit256(model, p));
}

}  // namespace

int correctness(double disparity, double groundTruth, bool denseGroundTruth) {
  if (!(groundTruth > 0.0)) return denseGroundTruth ? 0 : -1;
  const double error = std::abs(disparity - groundTruth);
  return error <= 3.0 || error <= 0.05 * groundTruth ? 1 : 0;
}

void collectConfidenceSamples(const ConfidenceInputs& inputs, const Image<std::int16_t>& disparity,
                              const EvalFrame& frame, int step, MatchMode mode, int paths,
                              std::vector<ConfidenceSample>& samples) {
  const int W = disparity.width();
  const int H = disparity.height();
  if (inputs.margin.empty()) throw std::invalid_argument("collectConfidenceSamples: the run had no confidence");
  const int wi = inputs.margin.width();
  const int hi = inputs.margin.height();
  for (int y = 0; y < H; y += step) {
    for (int x = 0; x < W; x += step) {
      if (disparity(x, y) == kInvalidDisparity) continue;
      const int score = correctness(disparity(x, y) / double(kDisparityScale), frame.groundTruth(x, y),
                                    frame.denseGroundTruth);
      if (score < 0) continue;
      const int xi = static_cast<int>(static_cast<long long>(x) * wi / W);
      const int yi = static_cast<int>(static_cast<long long>(y) * hi / H);
      ConfidenceSample s;
      s.pixel = confidencePixel(inputs, mode, paths, xi, yi);
      s.correct = score == 1;
      samples.push_back(s);
    }
  }
}

ConfidenceModel fitConfidenceModel(const std::vector<ConfidenceSample>& samples) {
  if (samples.empty()) throw std::invalid_argument("fitConfidenceModel: no samples");
  // Inputs scaled to about [0, 1] for a well-conditioned system; the weights are scaled back.
  const std::array<double, kFeatures> scale{1, 255, 16, 255, kLeftRightDifferenceCap, 1, kLidarDistanceCap, 4,
                                           255, 8, 1, kDisparityRangeCap, 2};
  Eigen::Matrix<double, kFeatures, 1> w = Eigen::Matrix<double, kFeatures, 1>::Zero();
  const double ridge = 1e-6 * static_cast<double>(samples.size());
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::Matrix<double, kFeatures, kFeatures> hessian = ridge * Eigen::Matrix<double, kFeatures, kFeatures>::Identity();
    hessian(0, 0) = 0;  // no ridge on the bias
    Eigen::Matrix<double, kFeatures, 1> gradient = -ridge * w;
    gradient(0) = 0;
    for (const ConfidenceSample& s : samples) {
      const std::array<double, kFeatures> f = featuresOf(s.pixel);
      Eigen::Matrix<double, kFeatures, 1> x;
      for (int i = 0; i < kFeatures; ++i) x(i) = f[static_cast<std::size_t>(i)] / scale[static_cast<std::size_t>(i)];
      const double p = 1.0 / (1.0 + std::exp(-w.dot(x)));
      gradient += ((s.correct ? 1.0 : 0.0) - p) * x;
      hessian.noalias() += std::max(p * (1.0 - p), 1e-9) * x * x.transpose();
    }
    const Eigen::Matrix<double, kFeatures, 1> delta = hessian.ldlt().solve(gradient);
    w += delta;
    if (delta.norm() < 1e-7) break;
  }
  std::array<int, kFeatures> q{};
  for (int i = 0; i < kFeatures; ++i) {
    q[static_cast<std::size_t>(i)] = static_cast<int>(std::lround(256.0 * w(i) / scale[static_cast<std::size_t>(i)]));
  }
  return ConfidenceModel{q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11], q[12]};
}

std::vector<ReliabilityBin> reliabilityDiagram(const std::vector<std::uint8_t>& confidence,
                                               const std::vector<bool>& correct, int bins) {
  if (confidence.size() != correct.size() || bins < 1) throw std::invalid_argument("reliabilityDiagram: bad input");
  std::vector<ReliabilityBin> out(static_cast<std::size_t>(bins));
  std::vector<double> sumConfidence(out.size(), 0.0), sumCorrect(out.size(), 0.0);
  for (std::size_t i = 0; i < confidence.size(); ++i) {
    const double p = confidence[i] / 255.0;
    const auto b = static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(p * bins)));
    sumConfidence[b] += p;
    sumCorrect[b] += correct[i] ? 1.0 : 0.0;
    ++out[b].count;
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].lower = static_cast<double>(b) / bins;
    out[b].upper = static_cast<double>(b + 1) / bins;
    if (out[b].count == 0) continue;
    out[b].meanConfidence = sumConfidence[b] / static_cast<double>(out[b].count);
    out[b].accuracy = sumCorrect[b] / static_cast<double>(out[b].count);
  }
  return out;
}

double expectedCalibrationError(const std::vector<ReliabilityBin>& bins) {
  double total = 0, error = 0;
  for (const ReliabilityBin& b : bins) {
    total += static_cast<double>(b.count);
    error += static_cast<double>(b.count) * std::abs(b.accuracy - b.meanConfidence);
  }
  return total > 0 ? error / total : 0.0;
}

namespace {

struct ModeRun {
  MatchMode mode;
  MethodKind kind;
  const char* name;
};
constexpr ModeRun kModes[] = {{MatchMode::StereoOnly, MethodKind::StereoSgm, "stereo_only"},
                              {MatchMode::LidarOnly, MethodKind::LidarSgm, "lidar_only"},
                              {MatchMode::Fused, MethodKind::FusedSgm, "fused"}};

std::vector<ConfidenceSample> samplesOf(const ModeRun& run, int firstSeed, int frames, int step,
                                        const ConfidenceFitOptions& options) {
  std::vector<ConfidenceSample> samples;
  for (const bool rain : {false, true}) {
    P3Options p3;
    p3.frames = frames;
    p3.firstSeed = static_cast<std::uint32_t>(firstSeed);
    p3.rain = rain;
    p3.width = options.width;
    p3.height = options.height;
    DensifierConfig config;
    config.matcher.threads = options.threads;
    for (const EvalFrame& frame : loadP3(p3)) {
      Method method;
      method.kind = run.kind;
      const MethodOutput out = runMethod(method, frame, config);
      collectConfidenceSamples(out.confidenceInputs, out.disparity, frame, step, run.mode, config.matcher.paths,
                               samples);
    }
  }
  return samples;
}

std::string modelText(const ConfidenceModel& m) {
  std::ostringstream os;
  os << "{" << m.bias << ", " << m.margin << ", " << m.marginLow << ", " << m.cost << ", " << m.leftRight << ", "
     << m.noCounterpart << ", " << m.lidarDistance << ", " << m.lidarDistanceLow << ", " << m.texture << ", "
     << m.textureLow << ", " << m.saturated << ", " << m.disparityRange << ", " << m.disparityRangeLow << "}";
  return os.str();
}

std::string reliabilityTable(const std::vector<ReliabilityBin>& bins) {
  std::ostringstream os;
  os << "| confidence | pixels | mean confidence | share correct |\n|---|---:|---:|---:|\n";
  char line[160];
  for (const ReliabilityBin& b : bins) {
    std::snprintf(line, sizeof(line), "| %.1f-%.1f | %zu | %.3f | %.3f |\n", b.lower, b.upper, b.count,
                  b.meanConfidence, b.accuracy);
    os << line;
  }
  return os.str();
}

}  // namespace

std::string runConfidenceFit(const ConfidenceFitOptions& options) {
  namespace fs = std::filesystem;
  fs::create_directories(options.out);
  std::ostringstream md;
  md << "# Confidence fit\n\nLogistic regression on P3 synthetic frames (clear and rain, 64 beams), "
     << options.trainFrames << " frames per set (seeds 300..), every " << options.step
     << "th pixel in x and y; checked on " << options.testFrames
     << " held-out frames per set (seeds 100.., the evaluation's), every 2nd pixel. Correct: |d - gt| <= 3 px or "
        "<= 5 %; a disparity where the GT has no surface (sky) is wrong.\n";
  PlotSpec plot;
  plot.title = "Reliability (P3 held-out frames)";
  plot.xLabel = "confidence / 255";
  plot.yLabel = "share correct";
  plot.fixedY = true;
  plot.series.push_back({"ideal", {0, 1}, {0, 1}, cv::Scalar(160, 160, 160), {}});
  const cv::Scalar colors[] = {cv::Scalar(200, 80, 0), cv::Scalar(0, 140, 0), cv::Scalar(0, 0, 220)};
  int c = 0;
  for (const ModeRun& run : kModes) {
    std::printf("  %s: fitting on %d + %d frames ...\n", run.name, options.trainFrames, options.trainFrames);
    std::fflush(stdout);
    const std::vector<ConfidenceSample> train = samplesOf(run, 300, options.trainFrames, options.step, options);
    const ConfidenceModel fitted = fitConfidenceModel(train);
    const std::vector<ConfidenceSample> test = samplesOf(run, 100, options.testFrames, 2, options);
    md << "\n## " << run.name << "\n\n" << train.size() << " training pixels, " << test.size()
       << " held-out pixels.\n\nFitted weights (bias, m, min(m,16), c, r, n, g, min(g,4), t, min(t,8), s, v, min(v,2)), 1/256 logit: `"
       << modelText(fitted) << "`; the library's: `" << modelText(confidenceModel(run.mode)) << "`.\n";
    for (const bool library : {true, false}) {
      const ConfidenceModel& model = library ? confidenceModel(run.mode) : fitted;
      std::vector<std::uint8_t> confidence;
      std::vector<bool> correct;
      for (const ConfidenceSample& s : test) {
        confidence.push_back(confidenceOf(model, s.pixel));
        correct.push_back(s.correct);
      }
      const std::vector<ReliabilityBin> bins = reliabilityDiagram(confidence, correct);
      char ece[160];
      std::snprintf(ece, sizeof(ece), "\n%s model on the held-out frames: expected calibration error %.4f\n\n",
                    library ? "The library's" : "The fitted", expectedCalibrationError(bins));
      md << ece << reliabilityTable(bins);
      if (library) {
        PlotSeries series{run.name, {}, {}, colors[c], {}};
        for (const ReliabilityBin& b : bins) {
          if (b.count < 100) continue;
          series.x.push_back(b.meanConfidence);
          series.y.push_back(b.accuracy);
        }
        plot.series.push_back(series);
      }
    }
    ++c;
  }
  io::writeImageAtomically(options.out + "/reliability.png", linePlot(plot));
  io::writeFileAtomically(options.out + "/confidence_fit.md", md.str());
  return md.str();
}

}  // namespace eval
}  // namespace lidar_sgm
