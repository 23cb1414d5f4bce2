#pragma once
/// @file confidence_fit.hpp  How the confidence models of core/confidence.hpp are fitted (logistic
/// regression on frames with exact GT) and checked (reliability diagram, expected calibration
/// error): `lidar_sgm_eval -fit_confidence`.

#include <cstdint>
#include <string>
#include <vector>

#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/eval/eval_frame.hpp"

namespace lidar_sgm {
namespace eval {

/// One pixel: its confidence inputs and whether its disparity is correct.
struct ConfidenceSample {
  ConfidencePixel pixel;
  bool correct = false;
};

/// KITTI's criterion, the one the confidence predicts: |d - gt| <= 3 px or <= 5 % of gt. A pixel
/// without GT is wrong where the GT is dense (no surface, e.g. sky) and not scored (returns -1)
/// where it is sparse; 1 = correct, 0 = wrong.
int correctness(double disparity, double groundTruth, bool denseGroundTruth);

/// Every `step`-th pixel (in x and y) with a disparity and a score. `inputs` may be at half the
/// disparity's size (scale 0.5): pixel (x, y) reads inputs at (x * w_in / w, y * h_in / h).
/// Each pixel's inputs as the model of `mode` reads them (confidencePixel).
void collectConfidenceSamples(const ConfidenceInputs& inputs, const Image<std::int16_t>& disparity,
                              const EvalFrame& frame, int step, MatchMode mode, int paths,
                              std::vector<ConfidenceSample>& samples);

/// Logistic regression (iteratively reweighted least squares, a small ridge so that inputs that
/// are constant, such as the texture in LiDAR-only mode, get weight 0), rounded to 1/64 logit.
ConfidenceModel fitConfidenceModel(const std::vector<ConfidenceSample>& samples);

/// One bin of a reliability diagram: the pixels whose confidence lies in [lower, upper).
struct ReliabilityBin {
  double lower = 0, upper = 0;
  double meanConfidence = 0;  ///< predicted probability (confidence / 255)
  double accuracy = 0;        ///< observed share correct
  std::size_t count = 0;
};

/// `bins` equal bins of confidence / 255 over (confidence, correct) pairs.
std::vector<ReliabilityBin> reliabilityDiagram(const std::vector<std::uint8_t>& confidence,
                                               const std::vector<bool>& correct, int bins = 10);
/// sum over bins of count * |accuracy - meanConfidence| / total: 0 for a perfectly calibrated map.
double expectedCalibrationError(const std::vector<ReliabilityBin>& bins);

struct ConfidenceFitOptions {
  std::string out;                    ///< folder for confidence_fit.md and the reliability plot
  int trainFrames = 4;                ///< per P3 set (clear 64, rain 64), seeds 300..
  int testFrames = 5;                 ///< held out, per set, seeds 100.. (the evaluation's frames)
  int width = 1242, height = 375;
  int step = 3;                       ///< pixel subsampling of the training set
  int threads = 0;
};

/// Fits the three models on the training frames, scores the current models (core/confidence.cpp)
/// and the fitted ones on the held-out frames, writes confidence_fit.md (the fitted weights as
/// C++ initialisers, the reliability tables, ECE) and reliability_<mode>.png. Returns the markdown.
std::string runConfidenceFit(const ConfidenceFitOptions& options);

}  // namespace eval
}  // namespace lidar_sgm
