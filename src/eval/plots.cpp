#include "plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "pictures.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

struct Range {
  double lo = 0, hi = 1;
};

/// Swaps reversed bounds and widens an empty range, so a step can always be computed.
Range normalized(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) throw std::invalid_argument("niceTicks: non-finite range");
  if (lo > hi) std::swap(lo, hi);
  if (lo == hi) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
  return {lo, hi};
}

/// Step of about (hi - lo) / target rounded to the nearest 1, 2 or 5 x 10^k: the "nice numbers"
/// of Heckbert, "Nice Numbers for Graph Labels" (Graphics Gems, 1990), thresholds 1.5 / 3 / 7.
double niceStep(const Range& range, int target) {
  const double raw = (range.hi - range.lo) / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / magnitude;
  double nice = 10.0;
  if (fraction < 1.5) {
    nice = 1.0;
  } else if (fraction < 3.0) {
    nice = 2.0;
  } else if (fraction < 7.0) {
    nice = 5.0;
  }
  return nice * magnitude;
}

/// Multiples of `step` inside [lo, hi]; the tolerance keeps bounds that are multiples up to
/// rounding (0.3 / 0.1 = 2.9999999999999996).
std::vector<double> multiplesInside(const Range& range, double step) {
  constexpr double kTolerance = 1e-9;
  const double first = std::ceil(range.lo / step - kTolerance);
  const double last = std::floor(range.hi / step + kTolerance);
  std::vector<double> ticks;
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

// ---------------------------------------------------------------------------------------------
// Layout and drawing

const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kGridGray(225, 225, 225);
const cv::Scalar kBorderGray(150, 150, 150);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTickScale = 0.4;
constexpr double kLabelScale = 0.45;
constexpr double kTitleScale = 0.55;
constexpr int kTargetTicks = 5;  // gives the 5-6 ticks a figure of this size can label legibly
constexpr int kMarkerRadius = 3;

/// One axis: the shown range (widened to whole ticks unless fixed) and its ticks.
struct Axis {
  Range range;
  std::vector<double> ticks;
  double step = 1;
};

Axis fittedAxis(double lo, double hi) {
  Axis axis;
  const Range data = normalized(lo, hi);
  axis.step = niceStep(data, kTargetTicks);
  axis.range = {std::floor(data.lo / axis.step) * axis.step, std::ceil(data.hi / axis.step) * axis.step};
  axis.ticks = multiplesInside(axis.range, axis.step);
  return axis;
}

Axis fixedAxis(double lo, double hi) {
  if (!(lo < hi)) throw std::invalid_argument("linePlot: fixed y range needs yMin < yMax");
  Axis axis;
  axis.range = {lo, hi};
  axis.step = niceStep(axis.range, kTargetTicks);
  axis.ticks = multiplesInside(axis.range, axis.step);
  return axis;
}

/// Data bounds over the finite values of every series ([0, 1] when there are none).
Range dataRange(const std::vector<PlotSeries>& series, bool useX) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const PlotSeries& s : series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const double v = useX ? s.x[i] : s.y[i];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (lo > hi) return {0.0, 1.0};
  return {lo, hi};
}

/// Tick labels show as many decimals as the step needs (0.2 -> "0.4", 0.05 -> "0.45", 5 -> "10").
std::string formatTick(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0.0"
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

cv::Size textSize(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline);
}

/// Maps data coordinates to pixels of the plot area (its own coordinates, y up). The range is
/// inset from the frame by a marker's size, so markers on the range's bounds are drawn whole.
struct Mapping {
  static constexpr int kInset = kMarkerRadius + 3;
  Axis x, y;
  cv::Rect area;
  double px(double v) const {
    return kInset + (v - x.range.lo) / (x.range.hi - x.range.lo) * (area.width - 1 - 2 * kInset);
  }
  double py(double v) const {
    return (area.height - 1 - kInset) - (v - y.range.lo) / (y.range.hi - y.range.lo) * (area.height - 1 - 2 * kInset);
  }
  cv::Point local(double vx, double vy) const { return {cvRound(px(vx)), cvRound(py(vy))}; }
};

void drawGridAndTicks(cv::Mat& canvas, const Mapping& m) {
  for (double t : m.x.ticks) {
    const int x = m.area.x + cvRound(m.px(t));
    cv::line(canvas, {x, m.area.y}, {x, m.area.br().y - 1}, kGridGray, 1);
    const std::string label = formatTick(t, m.x.step);
    const cv::Size size = textSize(label, kTickScale);
    cv::putText(canvas, label, {x - size.width / 2, m.area.br().y + 6 + size.height}, kFont, kTickScale, kBlack, 1,
                cv::LINE_AA);
  }
  for (double t : m.y.ticks) {
    const int y = m.area.y + cvRound(m.py(t));
    cv::line(canvas, {m.area.x, y}, {m.area.br().x - 1, y}, kGridGray, 1);
    const std::string label = formatTick(t, m.y.step);
    const cv::Size size = textSize(label, kTickScale);
    cv::putText(canvas, label, {m.area.x - 6 - size.width, y + size.height / 2}, kFont, kTickScale, kBlack, 1,
                cv::LINE_AA);
  }
  cv::rectangle(canvas, m.area, kBlack, 1);
}

/// The y label reads bottom to top: drawn horizontally on its own image, then rotated.
void drawVerticalText(cv::Mat& canvas, const std::string& text, int left, int centreY) {
  const cv::Size size = textSize(text, kLabelScale);
  cv::Mat horizontal(size.height + 8, size.width + 4, CV_8UC3, kWhite);
  cv::putText(horizontal, text, {2, size.height + 3}, kFont, kLabelScale, kBlack, 1, cv::LINE_AA);
  cv::Mat vertical;
  cv::rotate(horizontal, vertical, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect target(left, centreY - vertical.rows / 2, vertical.cols, vertical.rows);
  const cv::Rect clipped = target & cv::Rect(0, 0, canvas.cols, canvas.rows);
  if (clipped.empty()) return;
  vertical(cv::Rect(clipped.tl() - target.tl(), clipped.size())).copyTo(canvas(clipped));
}

void drawLabels(cv::Mat& canvas, const PlotSpec& spec, const cv::Rect& area) {
  if (!spec.title.empty()) {
    const cv::Size size = textSize(spec.title, kTitleScale);
    cv::putText(canvas, spec.title, {(canvas.cols - size.width) / 2, 8 + size.height}, kFont, kTitleScale, kBlack, 1,
                cv::LINE_AA);
  }
  if (!spec.xLabel.empty()) {
    const cv::Size size = textSize(spec.xLabel, kLabelScale);
    cv::putText(canvas, spec.xLabel, {area.x + (area.width - size.width) / 2, canvas.rows - 8}, kFont, kLabelScale,
                kBlack, 1, cv::LINE_AA);
  }
  if (!spec.yLabel.empty()) drawVerticalText(canvas, spec.yLabel, 2, area.y + area.height / 2);
}

/// Lines between consecutive finite points, and a marker at each; drawn into the plot area's
/// view so anything outside a fixed range is clipped at the axes.
void drawSeries(cv::Mat& canvas, const PlotSeries& s, const Mapping& m) {
  cv::Mat area = canvas(m.area);
  bool havePrevious = false;
  cv::Point previous;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      havePrevious = false;
      continue;
    }
    const cv::Point p = m.local(s.x[i], s.y[i]);
    if (havePrevious) cv::line(area, previous, p, s.color, 2, cv::LINE_AA);
    previous = p;
    havePrevious = true;
  }
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
      cv::circle(area, m.local(s.x[i], s.y[i]), kMarkerRadius, s.color, cv::FILLED, cv::LINE_AA);
    }
  }
  for (std::size_t i = 0; i < s.labels.size(); ++i) {
    if (s.labels[i].empty() || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
    const cv::Point p = m.local(s.x[i], s.y[i]) + cv::Point(kMarkerRadius + 2, -kMarkerRadius - 2);
    cv::putText(area, s.labels[i], p, kFont, kTickScale, s.color, 1, cv::LINE_AA);
  }
}

void drawLegend(cv::Mat& canvas, const std::vector<PlotSeries>& series, const cv::Rect& area) {
  if (series.empty()) return;
  constexpr int kRowHeight = 18, kPadding = 8, kSwatch = 24;
  int textWidth = 0;
  for (const PlotSeries& s : series) textWidth = std::max(textWidth, textSize(s.name, kTickScale).width);
  const int width = kPadding + kSwatch + 6 + textWidth + kPadding;
  const int height = 2 * kPadding - 4 + kRowHeight * static_cast<int>(series.size());
  const cv::Rect box(area.br().x - 8 - width, area.y + 8, width, height);
  cv::rectangle(canvas, box, kWhite, cv::FILLED);
  cv::rectangle(canvas, box, kBorderGray, 1);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const int centreY = box.y + kPadding - 2 + kRowHeight * static_cast<int>(i) + kRowHeight / 2;
    const int x0 = box.x + kPadding;
    cv::line(canvas, {x0, centreY}, {x0 + kSwatch, centreY}, series[i].color, 2, cv::LINE_AA);
    cv::circle(canvas, {x0 + kSwatch / 2, centreY}, kMarkerRadius, series[i].color, cv::FILLED, cv::LINE_AA);
    const cv::Size size = textSize(series[i].name, kTickScale);
    cv::putText(canvas, series[i].name, {x0 + kSwatch + 6, centreY + size.height / 2}, kFont, kTickScale, kBlack, 1,
                cv::LINE_AA);
  }
}

/// Room for the title above, tick labels and x label below, tick labels and y label left.
cv::Rect plotArea(const PlotSpec& spec) {
  const int left = spec.yLabel.empty() ? 56 : 74;
  const int right = 16;
  const int top = spec.title.empty() ? 14 : 34;
  const int bottom = spec.xLabel.empty() ? 28 : 48;
  return {left, top, spec.width - left - right, spec.height - top - bottom};
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (target < 1) throw std::invalid_argument("niceTicks: target = " + std::to_string(target) + ", must be >= 1");
  const Range range = normalized(lo, hi);
  return multiplesInside(range, niceStep(range, target));
}

cv::Mat linePlot(const PlotSpec& spec) {
  constexpr int kMinWidth = 160, kMinHeight = 120;  // below this, labels would overlap the data
  if (spec.width < kMinWidth || spec.height < kMinHeight) {
    throw std::invalid_argument("linePlot: size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                " is below the minimum 160x120");
  }
  for (const PlotSeries& s : spec.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("linePlot: series '" + s.name + "' has " + std::to_string(s.x.size()) + " x and " +
                                  std::to_string(s.y.size()) + " y values");
    }
    if (!s.labels.empty() && s.labels.size() != s.x.size()) {
      throw std::invalid_argument("linePlot: series '" + s.name + "' has " + std::to_string(s.labels.size()) +
                                  " labels for " + std::to_string(s.x.size()) + " points");
    }
  }
  Mapping mapping;
  mapping.area = plotArea(spec);
  const Range xData = dataRange(spec.series, true);
  const Range yData = dataRange(spec.series, false);
  mapping.x = fittedAxis(xData.lo, xData.hi);
  mapping.y = spec.fixedY ? fixedAxis(spec.yMin, spec.yMax) : fittedAxis(yData.lo, yData.hi);

  cv::Mat canvas(spec.height, spec.width, CV_8UC3, kWhite);
  drawGridAndTicks(canvas, mapping);
  drawLabels(canvas, spec, mapping.area);
  for (const PlotSeries& s : spec.series) drawSeries(canvas, s, mapping);
  drawLegend(canvas, spec.series, mapping.area);
  return canvas;
}

cv::Mat hconcat(const std::vector<cv::Mat>& images) {
  if (images.empty()) return {};
  int height = 0;
  for (const cv::Mat& image : images) height = std::max(height, image.rows);
  std::vector<cv::Mat> padded;
  for (const cv::Mat& image : images) {
    cv::Mat bgr = asBgr8(image);
    cv::copyMakeBorder(bgr, bgr, 0, height - bgr.rows, 0, 0, cv::BORDER_CONSTANT, kWhite);
    padded.push_back(bgr);
  }
  cv::Mat result;
  cv::hconcat(padded, result);
  return result;
}

}  // namespace eval
}  // namespace lidar_sgm
