#pragma once
/// @file sgm_densification.hpp  LiDAR-SGM as a PCL algorithm: sparse scan in, dense colored
/// cloud out.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/pcl/point_types.hpp"
#include "lidar_sgm/pipeline/config_options.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

/// The point types src/pcl/sgm_densification.cpp instantiates (Boost.PP sequences, as PCL's own):
/// the scans LiDAR drivers and maps give (x, y, z with intensity or color) in, and these out. Any
/// other type with x, y, z (the rest of PCL_XYZ_POINT_TYPES, a driver's own type): define
/// PCL_NO_PRECOMPILE before any PCL header, as for PCL's own classes (a type of PCL's own may also
/// include lidar_sgm/pcl/impl/sgm_densification.hpp).
#define LIDAR_SGM_PCL_INPUT_POINT_TYPES (pcl::PointXYZ)(pcl::PointXYZI)(pcl::PointXYZRGB)(pcl::PointXYZRGBA)
#define LIDAR_SGM_PCL_OUTPUT_POINT_TYPES (pcl::PointXYZ)(pcl::PointXYZRGB)(pcl::PointXYZRGBA)(pcl::PointXYZI)
/// The types with the per-point confidence (point_types.hpp), instantiated for these inputs.
#define LIDAR_SGM_PCL_CONFIDENCE_INPUT_POINT_TYPES (pcl::PointXYZ)(pcl::PointXYZI)
#define LIDAR_SGM_PCL_CONFIDENCE_OUTPUT_POINT_TYPES \
  (lidar_sgm::PointXYZConfidence)(lidar_sgm::PointXYZRGBConfidence)

namespace lidar_sgm {

/// Densifies a LiDAR scan by Semi-Global Matching on a LiDAR cost, a census (stereo) cost or
/// their fusion (LiDAR-SGM, Eq. 5), and returns the dense cloud, colored from the left image
/// when the output type has color.
///
/// Used like a PCL filter (the README's example; tests/pcl/test_readme_example.cpp compiles and
/// runs this exact text on data/sample):
/// @code
/// #include <lidar_sgm/io/calibration_io.hpp>
/// #include <lidar_sgm/io/cloud_io.hpp>
/// #include <lidar_sgm/io/image_io.hpp>
/// #include <lidar_sgm/pcl/sgm_densification.hpp>
/// #include <lidar_sgm/pcl/sgm_densification_opencv.hpp>
///
/// // One KITTI-layout frame, e.g. densify("data/sample", "000000").
/// pcl::PointCloud<pcl::PointXYZRGB> densify(const std::string& dir, const std::string& name) {
///   auto scan = lidar_sgm::io::readCloud(dir + "/velodyne/" + name + ".bin").makeShared();  // LiDAR frame
///   const cv::Mat left = lidar_sgm::io::readColorImage(dir + "/image_2/" + name + ".png");
///   const cv::Mat right = lidar_sgm::io::readColorImage(dir + "/image_3/" + name + ".png");
///
///   lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
///   sgm.setInputCloud(scan);                    // setIndices() is honoured
///   sgm.setCalibration(lidar_sgm::io::readCalibration(dir + "/calib/" + name + ".txt"));
///   lidar_sgm::setStereoPair(sgm, left, right); // cv::Mat; omit -> LiDAR-only SGM
///   sgm.setAlpha(0.7f);                         // LiDAR weight (Eq. 5); setConfig() sets everything
///   sgm.setNumberOfThreads(0);                  // 0 = all hardware threads; never changes the result
///   sgm.setKeepOrganized(false);                // setOutputFrame, setMaxDepth, setStride, setColorImage
///   pcl::PointCloud<pcl::PointXYZRGB> dense;
///   sgm.filter(dense);                          // empty + PCL_ERROR on bad input; getLastError() says why
///   return dense;                               // getDisparityImage(), getDepthImage(), getTimings()
/// }
/// @endcode
///
/// - Frames: the stereo pair and the color image belong to one frame. An object reused for
///   the next frame (setInputCloud() after a filter()) drops the images that were not given
///   again since that filter(): a frame without a pair is LiDAR-only and a frame without an
///   image is uncolored, whatever the object densified before and in whichever order the
///   setters are called. filter() again on the same cloud (a parameter sweep) keeps them.
/// - Mode: no stereo pair -> LiDAR-only SGM (alpha is not used); with a pair -> fused
///   (alpha in (0, 1]; alpha 0 keeps the LiDAR only for the left-right check's coverage).
/// - Indices set with setIndices() select the points that are projected; getProjectedLidar()'s
///   sourceIndex still refers to the input cloud, not to positions in the index list.
/// - Output: in the input's frame (header copied) by default; setOutputFrame(Camera) gives the
///   rectified left camera's frame, with frame_id from setCameraFrameId(). Organized output
///   (setKeepOrganized(true)) has one point per pixel (per stride step) with NaN where no
///   disparity was found and is_dense = false; unorganized output has valid points only.
/// - Color: from setColorImage(), else from the left image of the pair; written only when
///   PointOutT has color fields. Without any image the color fields keep their default.
/// - Intensity, written only when PointOutT has an intensity field (pcl::PointXYZI), per
///   output point's pixel: (1) where a LiDAR point of the input projected into that pixel and
///   PointInT has intensity, that point's intensity (the nearest one when several share the
///   pixel, as in the sparse disparity); (2) else, with a color image or a stereo pair, the
///   pixel's gray value in 0..255, unscaled (BT.601 weights, as pcl::PointXYZRGBtoXYZI and the
///   gray used for matching; a 16-bit pair gives its high byte); (3) else NaN.
/// - Errors (no input, empty cloud, invalid calibration or parameter, image size mismatch,
///   no point in the image) print PCL_ERROR naming the problem and leave the output empty;
///   getLastError() returns the message.
template <typename PointInT, typename PointOutT = pcl::PointXYZRGB>
class SGMDensification : public pcl::PCLBase<PointInT> {
 public:
  using Ptr = std::shared_ptr<SGMDensification<PointInT, PointOutT>>;
  using ConstPtr = std::shared_ptr<const SGMDensification<PointInT, PointOutT>>;
  using PointCloudIn = pcl::PointCloud<PointInT>;
  using PointCloudOut = pcl::PointCloud<PointOutT>;
  /// PCL's image type: an organized cloud of colors (from an organized RGB-D grabber, or
  /// io::toPclImage() from a cv::Mat; PCL 1.13 itself reads no PNG into a cloud).
  using ImageCloud = pcl::PointCloud<pcl::RGB>;

  SGMDensification() = default;
  ~SGMDensification() override = default;

  /// The scan of a frame (PCL's setInputCloud). After a filter(), it starts a new frame: the
  /// stereo pair and color image not given again since that filter() are dropped.
  void setInputCloud(const typename PointCloudIn::ConstPtr& cloud) override;

  // ---- calibration and images (sgm_densification_opencv.hpp adds cv::Mat overloads) --------

  void setCalibration(const geometry::StereoCalibration& calibration) { densifier_.setCalibration(calibration); }
  const geometry::StereoCalibration& getCalibration() const { return densifier_.calibration(); }

  /// Rectified left and right images, organized (width x height), same size. Converted to gray
  /// for matching (BT.601 weights, as OpenCV's BGR2GRAY); the left one also colors the output
  /// unless setColorImage() was called.
  void setStereoPair(const ImageCloud& left, const ImageCloud& right);
  /// 8- or 16-bit gray rectified pair (copied), both of the same depth, matched at that depth:
  /// ImageView<const uint8_t> or <const uint16_t> convert to it, as does io::grayView(cv::Mat).
  void setStereoPair(const GrayImageView& left, const GrayImageView& right);
  /// Back to LiDAR-only mode (also what the next frame gets when no pair is given for it).
  void clearStereoPair();
  /// The image that colors the output (organized, the rectified left camera's size); also
  /// colors a LiDAR-only result.
  void setColorImage(const ImageCloud& image);

  // ---- the configuration: everything the tools and Python set (pipeline/densifier_config.hpp)

  /// The whole configuration at once: matcher parameters, backend, search range, projection,
  /// filters, minimum confidence and the output cloud's frame, depth, stride and organisation.
  /// config_options.hpp reads one from options by name, as the command-line tools do:
  /// `sgm.setConfig(lidar_sgm::configFromOptions({{"alpha", "0.5"}}, {"no_lr_check"}))`.
  /// Throws std::invalid_argument naming the setting when `config` is invalid (the object keeps
  /// the configuration it had).
  void setConfig(const DensifierConfig& config) { densifier_.setConfig(config); }
  const DensifierConfig& getConfig() const { return densifier_.config(); }

  // Convenience setters for what PCL and OpenCV users set most (each changes one field of the
  // configuration; everything else goes through setConfig). Checked in filter().

  /// Every matcher parameter at once (lidar_sgm::Parameters: meanings and ranges there).
  void setParameters(const Parameters& params) { densifier_.setParameters(params); }
  const Parameters& getParameters() const { return densifier_.parameters(); }
  /// LiDAR weight of the fused cost (Eq. 5), in [0, 1].
  void setAlpha(float alpha) { densifier_.parameters().alpha = alpha; }
  float getAlpha() const { return densifier_.parameters().alpha; }
  /// The penalties of Eq. 1, as OpenCV's StereoSGBM names them.
  void setP1(int p1) { densifier_.parameters().P1 = p1; }
  int getP1() const { return densifier_.parameters().P1; }
  void setP2(int p2) { densifier_.parameters().P2 = p2; }
  int getP2() const { return densifier_.parameters().P2; }
  /// The search range: from each frame's LiDAR (DisparityRangeMode::FromLidar, the default:
  /// geometry::disparityRangeFromLidar) or the fixed [minDisparity, minDisparity +
  /// numDisparities) below (Fixed; the paper's [0, 128)). In FromLidar mode the fixed range is
  /// used only for a frame with no point in the image. getUsedDisparityRange() tells which.
  void setDisparityRangeMode(DisparityRangeMode mode) { densifier_.setDisparityRangeMode(mode); }
  DisparityRangeMode getDisparityRangeMode() const { return densifier_.disparityRangeMode(); }
  void setMinDisparity(int d) { densifier_.parameters().minDisparity = d; }
  int getMinDisparity() const { return densifier_.parameters().minDisparity; }
  void setNumDisparities(int n) { densifier_.parameters().numDisparities = n; }
  int getNumDisparities() const { return densifier_.parameters().numDisparities; }
  /// Matching resolution: 1 (default) or 0.5, the paper's half-scale mode (about 4x less work;
  /// numDisparities must then be a multiple of 32). The disparity image and an organized output
  /// keep the full size either way.
  void setScale(float scale) { densifier_.parameters().scale = scale; }
  float getScale() const { return densifier_.parameters().scale; }
  /// Matcher threads, 0 = all hardware threads (default). The result never depends on it.
  /// PCL's name, as pcl::NormalEstimationOMP::setNumberOfThreads.
  void setNumberOfThreads(int threads) { densifier_.parameters().threads = threads; }
  int getNumberOfThreads() const { return densifier_.parameters().threads; }
  /// The backend asked for (default Auto); getUsedBackend() tells which one matched.
  void setBackend(Backend backend) { densifier_.setBackend(backend); }
  Backend getBackend() const { return densifier_.backend(); }
  /// Points whose confidence is below `minConfidence` in [0, 1] are dropped (0 keeps every
  /// pixel); see Densifier::setMinConfidence. Throws std::invalid_argument outside [0, 1].
  void setMinConfidence(double minConfidence) { densifier_.setMinConfidence(minConfidence); }
  double getMinConfidence() const { return densifier_.minConfidence(); }

  // ---- the output cloud (geometry::ReprojectionOptions) ------------------------------------

  void setKeepOrganized(bool keep) { densifier_.reprojectionOptions().keepOrganized = keep; }
  bool getKeepOrganized() const { return densifier_.reprojectionOptions().keepOrganized; }
  void setOutputFrame(geometry::OutputFrame frame) { densifier_.reprojectionOptions().frame = frame; }
  geometry::OutputFrame getOutputFrame() const { return densifier_.reprojectionOptions().frame; }
  void setCameraFrameId(const std::string& frameId) { cameraFrameId_ = frameId; }
  const std::string& getCameraFrameId() const { return cameraFrameId_; }
  /// Output points deeper than this [m] are dropped (default 80 m; infinity keeps all).
  void setMaxDepth(double maxDepth) { densifier_.reprojectionOptions().maxDepth = maxDepth; }
  double getMaxDepth() const { return densifier_.reprojectionOptions().maxDepth; }
  /// Every `stride`-th pixel in x and y (default 1).
  void setStride(int stride) { densifier_.reprojectionOptions().stride = stride; }
  int getStride() const { return densifier_.reprojectionOptions().stride; }

  // ---- one frame and its results ----------------------------------------------------------

  /// Runs one frame. On error `output` is empty, PCL_ERROR says why, getLastError() too.
  void filter(PointCloudOut& output);

  /// The dense disparity of the last frame: x16 fixed point, kInvalidDisparity where none
  /// (io::toOpenCvDisparity() gives OpenCV's convention).
  const Image<std::int16_t>& getDisparityImage() const { return densifier_.disparity(); }
  /// The dense depth z [m] of the last frame in the left camera, 0 where there is none.
  const Image<float>& getDepthImage() const { return densifier_.depth(); }
  /// The last frame's confidence, 0..255 (Densifier::confidence()); output types with a
  /// `confidence` field (point_types.hpp) get it per point as confidence / 255.
  const Image<std::uint8_t>& getConfidenceImage() const { return densifier_.confidence(); }
  /// The projected scan of the last frame (sparse disparities, per-reason counts), empty after
  /// a failed one; sourceIndex[i] is the index of samples[i]'s point in the input cloud.
  const geometry::ProjectedLidar& getProjectedLidar() const { return projected_; }
  const DensificationTimings& getTimings() const { return densifier_.timings(); }
  /// The pixels the sky and outlier filters removed in the last run.
  const OutputFilterStats& getFilterStats() const { return densifier_.filterStats(); }
  MatchMode getLastMode() const { return densifier_.lastMode(); }
  /// The search range the last frame was matched with ("[0, 176) px from the LiDAR ...").
  const geometry::DisparityRange& getUsedDisparityRange() const { return densifier_.usedDisparityRange(); }
  /// The backend that matched the last frame (Auto resolved); Auto before the first.
  Backend getUsedBackend() const { return densifier_.usedBackend(); }
  const std::string& getLastError() const { return lastError_; }

  PCL_MAKE_ALIGNED_OPERATOR_NEW

 protected:
  using pcl::PCLBase<PointInT>::input_;
  using pcl::PCLBase<PointInT>::indices_;
  using pcl::PCLBase<PointInT>::initCompute;
  using pcl::PCLBase<PointInT>::deinitCompute;

  const std::string& getClassName() const { return className_; }

 private:
  void fail(PointCloudOut& output, const std::string& message);
  /// Hands the frame's color to the densifier and marks the frame's images as used.
  void useFrameImages();
  /// projected_ from the densifier's, with sourceIndex mapped through indices_ to the input.
  void takeProjected();
  /// Per pixel, the projected_ sample of the nearest point, -1 where there is none.
  void mapLidarPixels();
  /// The intensity rule of the class comment for the output point at pixel (x, y).
  float intensityAt(int x, int y) const;
  /// Output point i from the last run's cloud point i: a default point, then its fields (called
  /// on the Densifier's threads, one range of points each).
  void convertPoint(const geometry::DenseCloud& dense, const Image<std::uint8_t>& confidence, std::size_t i,
                    PointOutT& q) const;

  Densifier densifier_;
  std::vector<Eigen::Vector3f> points_;   ///< the indexed input points, kept between frames
  geometry::ProjectedLidar projected_;
  Image<std::int32_t> lidarPixel_;        ///< for the intensity rule only
  std::string className_ = "SGMDensification";
  std::string cameraFrameId_ = "camera_left_rect";
  std::string lastError_;
  /// The frame's images, each with whether it was given since the last filter() (a frame's
  /// own) and an error from a setter given unusable images, reported by filter().
  std::string pairError_;
  std::string colorError_;
  Image<Rgb8> pairColor_;      ///< the left image of a color pair; empty for a gray pair
  Image<Rgb8> explicitColor_;  ///< from setColorImage(): wins over pairColor_
  bool pairGivenSinceFilter_ = false;
  bool colorGivenSinceFilter_ = false;
  bool filteredSinceCloud_ = false;  ///< filter() ran since the last setInputCloud()
  bool colorChanged_ = false;        ///< the color to hand to the densifier changed since the last filter()
};

}  // namespace lidar_sgm

#ifdef PCL_NO_PRECOMPILE
#include "lidar_sgm/pcl/impl/sgm_densification.hpp"
#endif
