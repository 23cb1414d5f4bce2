#pragma once
/// @file densifier.hpp  One frame of LiDAR-SGM, end to end: project the scan, match, crop,
/// reproject. Every front end (the tools, the evaluation, the benches, SGMDensification) runs
/// this class, so what the evaluation measures is what the tools ship. No PCL, no OpenCV.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/core/image.hpp"
#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/core/matcher.hpp"
#include "lidar_sgm/core/parameters.hpp"
#include "lidar_sgm/geometry/calibration.hpp"
#include "lidar_sgm/geometry/disparity_range.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"
#include "lidar_sgm/pipeline/densifier_config.hpp"
#include "lidar_sgm/pipeline/output_filters.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"

namespace lidar_sgm {

class PostMatcherPasses;

/// Wall-clock time of the steps of the last run, in milliseconds.
struct DensificationTimings {
  double project = 0;    ///< cloud -> sparse LiDAR disparities (with the occlusion filter)
  double match = 0;      ///< LiDAR-SGM (all stages of the core), the LiDAR-only crop, the output filters
  double filters = 0;    ///< part of match: the LiDAR-only crop, the output filters, the confidence threshold
  double witness = 0;    ///< part of match: the stereo-only witness of the hidden-LiDAR check (hidden_lidar.hpp)
  double reproject = 0;  ///< dense disparity -> depth image and 3D points
  double total() const { return project + match + reproject; }
};

/// Holds the calibration, images, parameters and buffers between frames; run() does one frame.
///
/// @code
///   lidar_sgm::Densifier densifier;
///   densifier.setCalibration(calibration);           // K, baseline, T_cam_lidar, size
///   densifier.setStereoPair(left.view(), right.view());  // omit -> LiDAR-only SGM
///   densifier.parameters().alpha = 0.7f;              // LiDAR weight (Eq. 5)
///   const lidar_sgm::geometry::DenseCloud& cloud = densifier.run(points);  // LiDAR frame
///   // densifier.disparity(), densifier.depth(), densifier.projected() hold the rest.
/// @endcode
///
/// The mode follows the inputs: a stereo pair and LiDAR -> fused (Eq. 5, weight alpha); LiDAR
/// only -> LiDAR-only SGM (and, with the crop on, no pixel above the top / below the bottom beam);
/// a stereo pair only (runProjected(nullptr)) -> stereo-only census SGM. A third camera above the
/// left one (setUpCamera) adds the vertical census cost (Triple-SGM).
///
/// Errors are std::invalid_argument / std::runtime_error with a message naming the problem.
class Densifier {
 public:
  Densifier();
  ~Densifier();
  Densifier(Densifier&&) noexcept;
  Densifier& operator=(Densifier&&) noexcept;

  // ---- inputs ---------------------------------------------------------------------------

  void setCalibration(const geometry::StereoCalibration& calibration) { calibration_ = calibration; }
  const geometry::StereoCalibration& calibration() const { return calibration_; }

  /// The rectified gray pair (copied), 8 or 16 bit (both the same; any ImageView of uint8 /
  /// uint16 converts): census compares intensities, so 16-bit images lose nothing to 8 bits.
  /// Empty views clear the pair (LiDAR-only mode).
  void setStereoPair(const GrayImageView& left, const GrayImageView& right);
  void clearStereoPair();
  bool hasStereoPair() const { return !left_.empty() || !left16_.empty(); }
  /// The left image of the pair (8 or 16 bit; empty views without a pair).
  GrayImageView leftImage() const;

  /// A third rectified camera above the left one (same size and bit depth as the pair),
  /// `baselineRatio` = b_up / b in (0, 4]: its vertical census cost joins the stereo cost
  /// (Triple-SGM). Empty clears it.
  void setUpCamera(const GrayImageView& up, double baselineRatio);
  bool hasUpCamera() const { return !up_.empty() || !up16_.empty(); }

  /// Color for the output points (copied); empty clears it.
  void setColorImage(ImageView<const Rgb8> color);
  bool hasColorImage() const { return !color_.empty(); }

  // ---- options ----------------------------------------------------------------------------

  /// Everything the front ends can set, at once (densifier_config.hpp; config_options.hpp reads
  /// it from options by name). Throws std::invalid_argument, naming the setting, when `config` is
  /// invalid; the Densifier keeps its previous configuration then.
  void setConfig(const DensifierConfig& config);
  const DensifierConfig& config() const { return config_; }

  // The setters below change one part of config(); a run validates the whole.

  /// The matcher's parameters. Their minDisparity / numDisparities are the fixed range: used
  /// as given in DisparityRangeMode::Fixed, and in FromLidar only for frames without LiDAR.
  void setParameters(const Parameters& params) { config_.matcher = params; }
  const Parameters& parameters() const { return config_.matcher; }
  Parameters& parameters() { return config_.matcher; }
  void setBackend(Backend backend) { config_.backend = backend; }
  Backend backend() const { return config_.backend; }
  void setProjectionOptions(const geometry::ProjectionOptions& o) { config_.projection = o; }
  const geometry::ProjectionOptions& projectionOptions() const { return config_.projection; }
  geometry::ProjectionOptions& projectionOptions() { return config_.projection; }
  void setReprojectionOptions(const geometry::ReprojectionOptions& o) { config_.reprojection = o; }
  const geometry::ReprojectionOptions& reprojectionOptions() const { return config_.reprojection; }
  geometry::ReprojectionOptions& reprojectionOptions() { return config_.reprojection; }

  /// Where the search range comes from (default FromLidar) and, for FromLidar, the rule's numbers.
  void setDisparityRangeMode(DisparityRangeMode mode) { config_.rangeMode = mode; }
  DisparityRangeMode disparityRangeMode() const { return config_.rangeMode; }
  void setDisparityRangeRule(const geometry::DisparityRangeRule& rule) { config_.rangeRule = rule; }
  const geometry::DisparityRangeRule& disparityRangeRule() const { return config_.rangeRule; }

  /// LiDAR-only mode: clear the pixels above the scan's top and below its bottom point per
  /// column (+- lidarCoverageRows rows, +-2 columns), where nothing was measured (default on).
  void setCropToScan(bool crop) { config_.cropToScan = crop; }
  bool cropToScan() const { return config_.cropToScan; }

  /// Drop the pixels whose confidence (core/confidence.hpp) is below `minConfidence` in [0, 1]
  /// from the disparity, depth and cloud alike (0 keeps every pixel; default
  /// kDefaultMinConfidence). Needs parameters().confidence (a run throws otherwise when > 0).
  /// Throws std::invalid_argument outside [0, 1].
  void setMinConfidence(double minConfidence);
  double minConfidence() const { return config_.minConfidence; }
  /// The sky and outlier filters between matching and reprojection (output_filters.hpp; both on
  /// by default, in the modes with LiDAR): what they remove is missing from disparity(), depth()
  /// and the cloud alike.
  void setOutputFilters(const OutputFilterOptions& o) { config_.filters = o; }
  const OutputFilterOptions& outputFilters() const { return config_.filters; }
  OutputFilterOptions& outputFilters() { return config_.filters; }
  /// Whether a stereo pair that looks swapped (pair_orientation.hpp: the LiDAR's disparities,
  /// or without LiDAR most matches, find the right image on the wrong side) is refused with
  /// std::invalid_argument (default true). Off, it is matched as given.
  void setPairCheck(bool check) { config_.pairCheck = check; }
  bool pairCheck() const { return config_.pairCheck; }

  /// Whether run() also fills depth() and the dense cloud (default true). Off, a run stops at
  /// the disparity (what the disparity evaluation and the matcher benchmark need).
  void setComputeCloud(bool compute) { config_.computeCloud = compute; }
  bool computeCloud() const { return config_.computeCloud; }

  // ---- one frame ------------------------------------------------------------------------

  /// One frame from a cloud: `pointsLidar` in the LiDAR frame [m]. The image size is the
  /// calibration's, or the images' when the calibration has none (KITTI object files carry no
  /// size). Throws when the calibration, parameters or image sizes are invalid, the cloud is
  /// empty, or no point projects into the image. Returns cloud().
  const geometry::DenseCloud& run(const std::vector<Eigen::Vector3f>& pointsLidar);

  /// One frame from a scan already projected into the left image (e.g. a KITTI depth-completion
  /// sparse map): `lidar` null or empty -> stereo-only. The size is the images' or the LiDAR's.
  /// The calibration is optional here: without one (baseline 0) depth() and cloud() stay empty
  /// (then setComputeCloud(false) is implied); with one, its size must match. Returns cloud().
  const geometry::DenseCloud& runProjected(const LidarPoints* lidar);

  // ---- outputs of the last run ----------------------------------------------------------

  /// Dense disparity: int16 x16 fixed point (OpenCV's CV_16S convention), kInvalidDisparity
  /// (-32768) where there is none. io/opencv.hpp converts it to OpenCV's invalid value.
  const Image<std::int16_t>& disparity() const { return disparity_; }
  /// Per-pixel confidence, 0..255 ~ 255 x the probability that the disparity is correct
  /// (core/confidence.hpp), 0 where there is no disparity; empty when parameters().confidence
  /// is off.
  const Image<std::uint8_t>& confidence() const { return confidence_; }
  /// Dense depth z [m] in the left camera, from z = f*b/d (Eq. 3), 0 where there is no
  /// disparity or the depth exceeds the reprojection's maxDepth (KITTI's depth-completion
  /// convention: 0 = none). Empty when no cloud was computed.
  const Image<float>& depth() const { return depth_; }
  /// The dense cloud (LiDAR frame unless the reprojection options say camera).
  const geometry::DenseCloud& cloud() const { return cloud_; }
  /// Moves the last run's cloud out (cloud() is empty afterwards), for a front end that hands it
  /// on without a copy: every run makes a new cloud anyway.
  geometry::DenseCloud takeCloud() { return std::exchange(cloud_, geometry::DenseCloud()); }
  /// The projected scan: kept points with their pixel, x16 disparity and input index (for
  /// runProjected: the points of the LidarPoints in pixel order, sourceIndex empty).
  const geometry::ProjectedLidar& projected() const { return projected_; }
  /// The calibration the last run used (its size completed from the images).
  const geometry::StereoCalibration& usedCalibration() const { return used_; }
  /// The search range the last run matched with, and where it came from.
  const geometry::DisparityRange& usedDisparityRange() const { return usedRange_; }
  /// parameters() with the last run's range: what the matcher got (e.g. to color-map the
  /// disparity over [minDisparity, minDisparity + numDisparities)).
  const Parameters& usedParameters() const { return usedParams_; }
  const DensificationTimings& timings() const { return timings_; }
  /// The pixels the output filters removed in the last run.
  const OutputFilterStats& filterStats() const { return filterStats_; }
  /// The last run's votes on the pair's orientation (empty without a pair or the check).
  const PairOrientation& pairOrientation() const { return pairOrientation_; }
  MatchMode lastMode() const { return lastMode_; }
  /// The backend that matched (Auto resolved); Auto before the first run.
  Backend usedBackend() const;
  /// The matcher of the last run: its stage timings (lastTimings(), lastRescaleMs()) and LiDAR
  /// support; null before the first run.
  const Matcher* matcher() const { return matcher_.get(); }
  /// Percentage of pixels with a disparity in the last result.
  double validPercent() const;
  /// The color of pixel (x, y): from the color image, else from the left image (gray); false
  /// when there is neither.
  bool colorAt(int x, int y, Rgb8& out) const;
  /// Runs body(begin, end) on fixed contiguous ranges of [0, count), in parallel on the
  /// Densifier's threads (parameters().threads), for a front end that converts the last run's
  /// outputs element by element (the PCL class's points). The ranges depend on count and the
  /// thread count only; body must write each element the same way whichever range holds it.
  void parallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) const;

 private:
  geometry::StereoCalibration resolveCalibration(bool required, int lidarWidth, int lidarHeight) const;
  void prepareMatcher(const std::vector<LidarSample>& samples);
  void match(const LidarPoints* lidar);
  /// The stereo-only disparity the hidden-LiDAR check compares the points with (hidden_lidar.hpp).
  ImageView<const std::int16_t> matchStereoWitness(const GrayImageView& left, const GrayImageView& right,
                                                   const std::vector<LidarSample>& samples);
  void reprojectResult();
  template <typename T>
  void copyPair(ImageView<const T> left, ImageView<const T> right, Image<T>& leftOut, Image<T>& rightOut);

  geometry::StereoCalibration calibration_;
  geometry::StereoCalibration used_;
  DensifierConfig config_;
  Parameters usedParams_;
  geometry::DisparityRange usedRange_;
  Image<std::uint8_t> left_;
  Image<std::uint8_t> right_;
  Image<std::uint16_t> left16_;
  Image<std::uint16_t> right16_;
  Image<std::uint8_t> up_;
  Image<std::uint16_t> up16_;
  double upBaselineRatio_ = 0.0;
  Image<Rgb8> color_;
  std::unique_ptr<Matcher> matcher_;
  std::unique_ptr<PostMatcherPasses> passes_;  ///< the passes after the matcher, with their buffers
  Backend matcherBackend_ = Backend::Auto;  ///< the backend matcher_ was created for
  Image<std::int16_t> witnessDisparity_;  ///< the stereo-only witness of the hidden-LiDAR check
  // The witness below half scale of the pair: the pair halved here once or twice, and the
  // disparity of each halving's pair.
  std::array<Image<std::uint8_t>, 2> witnessLeft8_, witnessRight8_;
  std::array<Image<std::uint16_t>, 2> witnessLeft16_, witnessRight16_;
  std::array<Image<std::int16_t>, 2> witnessHalfDisparity_;
  std::vector<LidarSample> keptSamples_;  ///< the points left in the matching, buffer reused per frame
  LidarPoints lidar_;                     ///< the frame's projected points (run), buffers reused per frame
  LidarPoints keptLidar_;                 ///< ... those left in the matching, when some were dropped
  LidarAnchorBuffers anchorBuffers_;     ///< lidar_anchor.hpp's sums, reused per frame
  Image<std::int16_t> disparity_;
  Image<float> depth_;
  Image<std::uint8_t> confidence_;
  geometry::DenseCloud cloud_;
  geometry::ProjectedLidar projected_;
  DensificationTimings timings_;
  OutputFilterStats filterStats_;
  MatchMode lastMode_ = MatchMode::LidarOnly;
  PairOrientation pairOrientation_;
  bool haveCalibration_ = false;  ///< the last run had a calibration (depth and cloud possible)
};

}  // namespace lidar_sgm
