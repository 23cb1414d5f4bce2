#pragma once
/// @file plots.hpp  A small line-plot renderer on cv::Mat (the evaluation's sweep figures; no
/// plotting library is a dependency).

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lidar_sgm {
namespace eval {

/// One line of a plot: points (x[i], y[i]) joined in order, with a marker at each. Non-finite
/// points are skipped and break the line.
struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  cv::Scalar color;  ///< BGR
  /// Optional: a text beside each point (empty, or as many as x; an empty text draws nothing).
  std::vector<std::string> labels;
};

struct PlotSpec {
  std::string title, xLabel, yLabel;
  std::vector<PlotSeries> series;
  int width = 640, height = 420;
  /// Fixed y range [yMin, yMax] instead of one fitted to the data (e.g. 0..1 for shares).
  bool fixedY = false;
  double yMin = 0, yMax = 1;
};

/// "Nice" tick positions (step 1, 2 or 5 x 10^k, about `target` intervals) inside [lo, hi],
/// ascending. lo > hi is swapped; lo == hi gets a range around it. Throws std::invalid_argument
/// for non-finite bounds or target < 1.
std::vector<double> niceTicks(double lo, double hi, int target = 5);

/// Renders `spec` as an 8-bit BGR image of width x height: white background, axes with nice
/// ticks and labels, grid, lines with markers, legend box top-right. Throws
/// std::invalid_argument when a series' x and y (or its non-empty labels) differ in length or the size
/// is too small.
cv::Mat linePlot(const PlotSpec& spec);

/// Side-by-side images (8-bit gray or BGR; the result is BGR), shorter ones padded with white at
/// the bottom. Empty input gives an empty Mat.
cv::Mat hconcat(const std::vector<cv::Mat>& images);

}  // namespace eval
}  // namespace lidar_sgm
