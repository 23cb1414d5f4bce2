#include "lidar_sgm/pipeline/densifier.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "lidar_sgm/geometry/scan_extent.hpp"
#include "lidar_sgm/pipeline/hidden_lidar.hpp"
#include "lidar_sgm/pipeline/lidar_anchor.hpp"
#include "lidar_sgm/pipeline/min_confidence.hpp"
#include "core/half_scale.hpp"
#include "core/parallel_ranges.hpp"
#include "pipeline/post_matcher_passes.hpp"

namespace lidar_sgm {

namespace {

/// The passes around the matcher for `backend` (resolved) on `threads`, created on first use.
void selectPasses(std::unique_ptr<PostMatcherPasses>& passes, Backend backend, int threads) {
  if (!passes) passes = std::make_unique<PostMatcherPasses>();
  passes->select(backend, threads);
}

template <typename T>
void copyInto(ImageView<const T> from, Image<T>& to) {
  to.resize(from.width, from.height);
  for (int y = 0; y < from.height; ++y) std::copy(from.row(y), from.row(y) + from.width, to.view().row(y));
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <typename T>
void checkPair(ImageView<const T> left, ImageView<const T> right) {
  if (left.empty() != right.empty()) {
    throw std::invalid_argument("setStereoPair: give both images or neither");
  }
  if (left.width != right.width || left.height != right.height) {
    throw std::invalid_argument("setStereoPair: the left image is " + sizeText(left.width, left.height) +
                                " but the right image is " + sizeText(right.width, right.height));
  }
}

/// The samples of a per-pixel LiDAR image, in pixel order: what the crop and projected() need.
std::vector<LidarSample> samplesOf(const LidarPoints& lidar) {
  std::vector<LidarSample> samples;
  samples.reserve(lidar.size());
  for (int y = 0; y < lidar.height(); ++y) {
    for (int x = 0; x < lidar.width(); ++x) {
      for (const int* d = lidar.begin(x, y); d != lidar.end(x, y); ++d) samples.push_back({x, y, *d});
    }
  }
  return samples;
}

}  // namespace

Densifier::Densifier() = default;
Densifier::~Densifier() = default;
Densifier::Densifier(Densifier&&) noexcept = default;
Densifier& Densifier::operator=(Densifier&&) noexcept = default;

template <typename T>
void Densifier::copyPair(ImageView<const T> left, ImageView<const T> right, Image<T>& leftOut, Image<T>& rightOut) {
  checkPair(left, right);
  clearStereoPair();
  if (left.empty()) return;
  copyInto(left, leftOut);
  copyInto(right, rightOut);
}

void Densifier::setStereoPair(const GrayImageView& left, const GrayImageView& right) {
  if (!left.gray16.empty() || !right.gray16.empty()) {
    if (!left.gray8.empty() || !right.gray8.empty()) {
      throw std::invalid_argument("setStereoPair: the left and right images differ in bit depth (8 vs 16 bit)");
    }
    copyPair(left.gray16, right.gray16, left16_, right16_);
  } else {
    copyPair(left.gray8, right.gray8, left_, right_);
  }
}

void Densifier::clearStereoPair() {
  left_ = Image<std::uint8_t>();
  right_ = Image<std::uint8_t>();
  left16_ = Image<std::uint16_t>();
  right16_ = Image<std::uint16_t>();
}

GrayImageView Densifier::leftImage() const {
  if (!left16_.empty()) return GrayImageView(left16_.view());
  return GrayImageView(left_.view());
}

void Densifier::setUpCamera(const GrayImageView& up, double baselineRatio) {
  up_ = Image<std::uint8_t>();
  up16_ = Image<std::uint16_t>();
  upBaselineRatio_ = 0.0;
  if (up.empty()) return;
  if (!(baselineRatio > 0.0 && baselineRatio <= 4.0)) {
    throw std::invalid_argument("setUpCamera: the baseline ratio b_up / b must be in (0, 4], got " +
                                std::to_string(baselineRatio));
  }
  if (!up.gray16.empty()) {
    copyInto(up.gray16, up16_);
  } else {
    copyInto(up.gray8, up_);
  }
  upBaselineRatio_ = baselineRatio;
}

void Densifier::setColorImage(ImageView<const Rgb8> color) {
  if (color.empty()) {
    color_ = Image<Rgb8>();
    return;
  }
  copyInto(color, color_);
}

geometry::StereoCalibration Densifier::resolveCalibration(bool required, int lidarWidth, int lidarHeight) const {
  geometry::StereoCalibration c = calibration_;
  // The images fix the size when the calibration file had none; otherwise they must agree.
  const auto adopt = [&c](int width, int height, const char* what) {
    if (c.width == 0 && c.height == 0) {
      c.width = width;
      c.height = height;
    } else if (c.width != width || c.height != height) {
      throw std::invalid_argument(std::string("the ") + what + " is " + sizeText(width, height) +
                                  " but the calibration is for " + sizeText(c.width, c.height));
    }
  };
  if (!left_.empty()) adopt(left_.width(), left_.height(), "stereo pair");
  if (!left16_.empty()) adopt(left16_.width(), left16_.height(), "stereo pair");
  if (!up_.empty()) adopt(up_.width(), up_.height(), "third camera's image");
  if (!up16_.empty()) adopt(up16_.width(), up16_.height(), "third camera's image");
  if (!color_.empty()) adopt(color_.width(), color_.height(), "color image");
  if (lidarWidth > 0 || lidarHeight > 0) adopt(lidarWidth, lidarHeight, "projected LiDAR image");
  if (c.width == 0 && c.height == 0) {
    throw std::invalid_argument(
        "the calibration has no image size and there is no image to take it from: set a stereo pair, a color "
        "image, or a calibration with a size");
  }
  if (required || calibration_.baseline != 0.0) {
    c.validate();
  } else if (c.width <= 0 || c.height <= 0) {
    throw std::invalid_argument("the image size " + sizeText(c.width, c.height) + " is not positive");
  }
  return c;
}

void Densifier::prepareMatcher(const std::vector<LidarSample>& samples) {
  // The range depends on the frame: chosen here, after the projection, and validated with the rest.
  usedRange_ = geometry::disparityRangeFromLidar(
      config_.rangeMode == DisparityRangeMode::FromLidar ? samples : std::vector<LidarSample>{}, config_.matcher, config_.rangeRule);
  usedParams_ = config_.matcher;
  usedParams_.minDisparity = usedRange_.minDisparity;
  usedParams_.numDisparities = usedRange_.numDisparities;
  validate(usedParams_);
  // The matcher keeps its buffers between frames; it is rebuilt only for another backend.
  if (!matcher_ || matcherBackend_ != config_.backend) {
    matcher_ = Matcher::create(config_.backend, usedParams_);
    matcherBackend_ = config_.backend;
  } else {
    matcher_->setParameters(usedParams_);
  }
}

void Densifier::match(const LidarPoints* lidar) {
  const auto start = std::chrono::steady_clock::now();
  const bool useLidar = lidar != nullptr && !lidar->empty();
  if (!useLidar && !hasStereoPair()) {
    throw std::invalid_argument("nothing to match: give LiDAR points, a stereo pair, or both");
  }
  if (hasUpCamera() && !hasStereoPair()) {
    throw std::invalid_argument("the third camera needs the stereo pair it extends");
  }
  if (hasUpCamera() && up16_.empty() != left16_.empty()) {
    throw std::invalid_argument("the third camera's image and the stereo pair differ in bit depth");
  }
  disparity_.resize(used_.width, used_.height);
  VerticalView up;
  if (!up_.empty()) up.up = up_.view();
  if (!up16_.empty()) up.up = up16_.view();
  up.baselineRatio = upBaselineRatio_;
  GrayImageView left;
  GrayImageView right;
  if (!left_.empty()) {
    left = left_.view();
    right = right_.view();
  } else if (!left16_.empty()) {
    left = left16_.view();
    right = right16_.view();
  }
  selectPasses(passes_, matcher_->backend(), effectiveThreads(usedParams_));
  pairOrientation_ = PairOrientation();
  if (config_.pairCheck && !left.empty()) {
    pairOrientation_ = useLidar ? passes_->pairOrientationFromLidar(left, right, projected_.samples)
                                : passes_->pairOrientationFromStereo(left, right, usedParams_.minDisparity,
                                                                     usedParams_.numDisparities);
    if (pairOrientation_.looksSwapped()) throw std::invalid_argument(swappedPairMessage(pairOrientation_));
  }
  // The points the camera sees a nearer surface in front of (hidden_lidar.hpp), then those the
  // pair contradicts (lidar_consistency.hpp), are left out of the matching; the projected scan
  // keeps them.
  std::size_t hidden = 0;
  std::size_t inconsistent = 0;
  timings_.witness = 0.0;
  if (useLidar && !left.empty() && (config_.hiddenLidar.enabled || config_.lidarConsistency.enabled)) {
    std::vector<LidarSample>& samples = keptSamples_;
    samples = projected_.samples;  // the scan's samples, already at hand; the buffer is reused
    if (config_.hiddenLidar.enabled) {
      const auto witnessStart = std::chrono::steady_clock::now();
      hidden = dropHiddenLidar(matchStereoWitness(left, right, samples), *lidar, samples, config_.hiddenLidar);
      timings_.witness = millisecondsSince(witnessStart);
    }
    if (config_.lidarConsistency.enabled) inconsistent = dropInconsistentLidar(left, right, samples, config_.lidarConsistency);
    if (hidden + inconsistent > 0) {
      keptLidar_.assign(lidar->width(), lidar->height(), samples);
      lidar = &keptLidar_;
    }
  }
  matcher_->compute(left, right, up, useLidar ? lidar : nullptr, disparity_.view());
  lastMode_ = matcher_->lastMode();
  const auto filtersStart = std::chrono::steady_clock::now();
  if (config_.cropToScan && lastMode_ == MatchMode::LidarOnly) {
    // +-2 columns bridges the gaps between a beam's points (KITTI: ~1 px apart, with dropouts).
    geometry::cropToScanRows(disparity_.view(), projected_.samples, config_.matcher.lidarCoverageRows, 2);
  }
  filterStats_ = useLidar ? passes_->applyOutputFilters(disparity_.view(), projected_.samples, left, config_.filters)
                          : OutputFilterStats{};
  // The far scene's sub-pixel disparity from the points left in the matching (lidar_anchor.hpp).
  const std::vector<LidarSample>& anchorSamples = hidden + inconsistent > 0 ? keptSamples_ : projected_.samples;
  filterStats_.anchored =
      useLidar ? passes_->anchorToLidar(disparity_.view(), anchorSamples, config_.lidarAnchor, anchorBuffers_) : 0;
  filterStats_.inconsistentLidar = inconsistent;
  filterStats_.hiddenLidar = hidden;
  // The matcher's confidence, 0 where a later step removed the disparity; then the threshold.
  passes_->confidenceOfValidPixels(disparity_.view(), matcher_->confidence(), config_.minConfidence, confidence_);
  timings_.filters = millisecondsSince(filtersStart);
  timings_.match = millisecondsSince(start);
}

namespace {

int floorHalf(int value) { return value >= 0 ? value / 2 : -((-value + 1) / 2); }

}  // namespace

ImageView<const std::int16_t> Densifier::matchStereoWitness(const GrayImageView& left, const GrayImageView& right,
                                                            const std::vector<LidarSample>& samples) {
  // Stereo alone over the fused frame's range, with the left-right check whatever the fused
  // settings (an occluded pixel must have no vote) and without the confidence nobody reads. Its
  // scale is relative to the frame's: a half-scale frame's witness at the default 0.5 is matched
  // at a quarter of the pair's pixels, as a full-scale frame's at half of them (the paper's fast
  // mode keeps the witness at an eighth of its matching). Below half scale of the pair, the pair
  // is halved here (once or twice), then matched at half scale. The fused matcher does it, before
  // its own frame: its buffers serve both.
  Parameters p = usedParams_;
  p.lrCheck = true;
  p.confidence = false;
  const float scale = usedParams_.scale * config_.hiddenLidar.witnessScale;
  const int halvings = scale >= 0.5f ? 0 : scale >= 0.25f ? 1 : 2;  // of the pair, here
  for (int i = 0; i < halvings; ++i) {
    // The halved pair's range: half of the frame's, widened to whole pixels.
    const int end = -floorHalf(-(p.minDisparity + p.numDisparities));
    p.minDisparity = floorHalf(p.minDisparity);
    p.numDisparities = end - p.minDisparity;
  }
  p.scale = scale == 1.0f ? 1.0f : 0.5f;
  if (p.scale != 1.0f) {
    // Half scale searches half the range: an even start and a multiple of 32 that still covers it.
    const int end = p.minDisparity + p.numDisparities;
    p.minDisparity -= ((p.minDisparity % 2) + 2) % 2;
    p.numDisparities = std::min(512, 32 * ((end - p.minDisparity + 31) / 32));  // 512: the largest range
  }
  // The witness is read only at the points' pixels: it is matched on the rows the points span,
  // with a margin for the paths to settle, starting on a whole block of the scaled pair (so its
  // halved rows are those of the whole pair halved); the rows outside have no disparity.
  const int block = p.scale == 1.0f ? 1 : 2 << halvings;
  const WitnessRows rows = witnessRows(samples, left.height(), config_.hiddenLidar.witnessMarginRows, block);
  witnessDisparity_.resize(left.width(), left.height());
  const std::ptrdiff_t width = left.width();
  std::fill(witnessDisparity_.data(), witnessDisparity_.data() + rows.begin * width, kInvalidDisparity);
  std::fill(witnessDisparity_.data() + rows.end * width, witnessDisparity_.data() + left.height() * width,
            kInvalidDisparity);
  if (rows.end <= rows.begin) return witnessDisparity_.view();
  GrayImageView pairLeft = rowsOf(left, rows.begin, rows.end);
  GrayImageView pairRight = rowsOf(right, rows.begin, rows.end);
  for (int i = 0; i < halvings; ++i) {
    pairLeft = downscaleHalf(pairLeft, witnessLeft8_[i], witnessLeft16_[i]);
    pairRight = downscaleHalf(pairRight, witnessRight8_[i], witnessRight16_[i]);
    witnessHalfDisparity_[i].resize(pairLeft.width(), pairLeft.height());
  }
  matcher_->setParameters(p);
  // The last halving's pair is matched, its disparity brought up through each halving's size.
  const ImageView<std::int16_t> band = rowsOf(witnessDisparity_.view(), rows.begin, rows.end);
  matcher_->compute(pairLeft, pairRight, nullptr, halvings == 0 ? band : witnessHalfDisparity_[halvings - 1].view());
  for (int i = halvings - 1; i >= 0; --i) {
    upscaleDisparity(std::as_const(witnessHalfDisparity_[i]).view(), i == 0 ? band : witnessHalfDisparity_[i - 1].view());
  }
  matcher_->setParameters(usedParams_);
  return witnessDisparity_.view();
}

void Densifier::setMinConfidence(double minConfidence) {
  confidenceThreshold(minConfidence);  // validates
  config_.minConfidence = minConfidence;
}

void Densifier::setConfig(const DensifierConfig& config) {
  validate(config);
  config_ = config;
}

void Densifier::reprojectResult() {
  const auto start = std::chrono::steady_clock::now();
  if (config_.computeCloud && haveCalibration_) {
    // Into last frame's depth image and cloud: their memory is reused.
    passes_->reproject(disparity_.view(), used_, config_.reprojection, depth_, cloud_);
  } else {
    cloud_ = geometry::DenseCloud();
    depth_ = Image<float>();
  }
  timings_.reproject = millisecondsSince(start);
}

const geometry::DenseCloud& Densifier::run(const std::vector<Eigen::Vector3f>& pointsLidar) {
  used_ = resolveCalibration(true, 0, 0);
  haveCalibration_ = true;
  validate(config_);  // the whole configuration, in one place (densifier_config.hpp)
  if (pointsLidar.empty()) throw std::invalid_argument("the input cloud is empty");

  const auto start = std::chrono::steady_clock::now();
  // Before the matcher exists (its range comes from this projection): the backend it will run.
  selectPasses(passes_, matcher_ && matcherBackend_ == config_.backend ? matcher_->backend() : resolve(config_.backend),
               effectiveThreads(config_.matcher));
  passes_->project(pointsLidar, used_, config_.projection, projected_);
  timings_.project = millisecondsSince(start);
  if (projected_.samples.empty()) {
    throw std::invalid_argument("no point of the cloud projects into the image (" + projected_.stats.describe() +
                                "): check the calibration");
  }
  prepareMatcher(projected_.samples);
  lidar_.assign(projected_.width, projected_.height, projected_.samples);
  match(&lidar_);
  reprojectResult();
  return cloud_;
}

const geometry::DenseCloud& Densifier::runProjected(const LidarPoints* lidar) {
  const bool useLidar = lidar != nullptr && !lidar->empty();
  used_ = resolveCalibration(false, useLidar ? lidar->width() : 0, useLidar ? lidar->height() : 0);
  haveCalibration_ = calibration_.baseline != 0.0;
  validate(config_);  // the whole configuration, in one place (densifier_config.hpp)
  const auto start = std::chrono::steady_clock::now();
  projected_ = geometry::ProjectedLidar();
  projected_.width = used_.width;
  projected_.height = used_.height;
  if (useLidar) {
    projected_.samples = samplesOf(*lidar);
    projected_.stats.input = projected_.samples.size();
    projected_.stats.kept = projected_.samples.size();
  }
  timings_.project = millisecondsSince(start);
  prepareMatcher(projected_.samples);
  match(useLidar ? lidar : nullptr);
  reprojectResult();
  return cloud_;
}

Backend Densifier::usedBackend() const { return matcher_ ? matcher_->backend() : Backend::Auto; }

double Densifier::validPercent() const {
  if (disparity_.empty()) return 0.0;
  std::size_t valid = 0;
  for (int y = 0; y < disparity_.height(); ++y) {
    for (int x = 0; x < disparity_.width(); ++x) valid += disparity_(x, y) != kInvalidDisparity ? 1 : 0;
  }
  return 100.0 * static_cast<double>(valid) / (static_cast<double>(disparity_.width()) * disparity_.height());
}

void Densifier::parallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) const {
  // parallelParts takes an int count: larger counts go in int-sized blocks.
  constexpr std::size_t kBlock = static_cast<std::size_t>(std::numeric_limits<int>::max());
  for (std::size_t offset = 0; offset < count; offset += kBlock) {
    const int n = static_cast<int>(std::min(kBlock, count - offset));
    parallelParts(n, effectiveThreads(config_.matcher), [&](int, int begin, int end) {
      body(offset + static_cast<std::size_t>(begin), offset + static_cast<std::size_t>(end));
    });
  }
}

bool Densifier::colorAt(int x, int y, Rgb8& out) const {
  if (!color_.empty()) {
    out = color_(x, y);
    return true;
  }
  if (!left_.empty()) {
    const std::uint8_t g = left_(x, y);
    out = Rgb8{g, g, g};
    return true;
  }
  if (!left16_.empty()) {
    const auto g = static_cast<std::uint8_t>(left16_(x, y) >> 8);
    out = Rgb8{g, g, g};
    return true;
  }
  return false;
}

}  // namespace lidar_sgm
