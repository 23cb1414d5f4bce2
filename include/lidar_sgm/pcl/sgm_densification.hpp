#pragma once
/// @file sgm_densification.hpp  LiDAR-SGM as a PCL algorithm: sparse scan in, dense colored
/// cloud out.

#include <memory>
#include <string>

#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {

/// Densifies a LiDAR scan by Semi-Global Matching on a LiDAR cost, a census (stereo) cost or
/// their fusion (LiDAR-SGM, Eq. 5), and returns the dense cloud, colored from the left image
/// when the output type has color.
///
/// Used like a PCL filter:
/// @code
///   lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB> sgm;
///   sgm.setInputCloud(scan);                                  // LiDAR frame
///   sgm.setCalibration(lidar_sgm::io::readCalibration("calib.txt"));
///   sgm.setStereoPair(left, right);   // organized pcl::PointCloud<pcl::RGB>; omit -> LiDAR-only
///   sgm.setAlpha(0.7f);               // LiDAR weight (Eq. 5)
///   pcl::PointCloud<pcl::PointXYZRGB> dense;
///   sgm.filter(dense);                // empty + PCL_ERROR on bad input
/// @endcode
///
/// - Mode: no stereo pair -> LiDAR-only SGM (alpha is not used); with a pair -> fused
///   (alpha in (0, 1]; alpha 0 keeps the LiDAR only for the left-right check's coverage).
/// - Indices set with setIndices() select the points that are projected.
/// - Output: in the input's frame (header copied) by default; setOutputFrame(Camera) gives the
///   rectified left camera's frame, with frame_id from setCameraFrameId(). Organized output
///   (setKeepOrganized(true)) has one point per pixel (per stride step) with NaN where no
///   disparity was found and is_dense = false; unorganized output has valid points only.
/// - Color: from setColorImage(), else from the left image of the pair; written only when
///   PointOutT has color fields. Without any image the color fields keep their default.
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
  /// PCL's image type: an organized cloud of colors (e.g. from pcl::io::loadPNGFile or an
  /// organized RGB-D grabber).
  using ImageCloud = pcl::PointCloud<pcl::RGB>;

  SGMDensification() = default;
  ~SGMDensification() override = default;

  void setCalibration(const geometry::StereoCalibration& calibration) { pipeline_.setCalibration(calibration); }
  const geometry::StereoCalibration& getCalibration() const { return pipeline_.calibration(); }

  /// Rectified left and right images, organized (width x height), same size. Converted to gray
  /// for matching (BT.601 weights, as OpenCV's BGR2GRAY); the left one also colors the output
  /// unless setColorImage() was called.
  void setStereoPair(const ImageCloud& left, const ImageCloud& right);
  /// 8-bit gray rectified pair (copied).
  void setStereoPair(ImageView<const std::uint8_t> left, ImageView<const std::uint8_t> right);
  /// 16-bit gray rectified pair (copied); matched at full depth.
  void setStereoPair(ImageView<const std::uint16_t> left, ImageView<const std::uint16_t> right);
  /// Back to LiDAR-only mode.
  void clearStereoPair();
  /// The image that colors the output (organized, the rectified left camera's size); also
  /// colors a LiDAR-only result.
  void setColorImage(const ImageCloud& image);

  void setAlpha(float alpha) { pipeline_.parameters().alpha = alpha; }
  float getAlpha() const { return pipeline_.parameters().alpha; }
  void setSigma(float sigma) { pipeline_.parameters().sigma = sigma; }
  float getSigma() const { return pipeline_.parameters().sigma; }
  void setNumDisparities(int n) { pipeline_.parameters().numDisparities = n; }
  int getNumDisparities() const { return pipeline_.parameters().numDisparities; }
  void setP1(int p1) { pipeline_.parameters().P1 = p1; }
  int getP1() const { return pipeline_.parameters().P1; }
  void setP2(int p2) { pipeline_.parameters().P2 = p2; }
  int getP2() const { return pipeline_.parameters().P2; }
  void setPaths(int paths) { pipeline_.parameters().paths = paths; }
  int getPaths() const { return pipeline_.parameters().paths; }
  /// Matching resolution: 1 (default) or 0.5, the paper's half-scale mode (about 4x less work;
  /// numDisparities must then be a multiple of 32). The disparity image and an organized output
  /// keep the full size either way. Checked in filter().
  void setScale(float scale) { pipeline_.parameters().scale = scale; }
  float getScale() const { return pipeline_.parameters().scale; }
  /// Matcher threads, 0 = all hardware threads (default); in [0, 256], checked in filter(). The
  /// result never depends on it. PCL's name, as pcl::NormalEstimationOMP::setNumberOfThreads.
  void setNumberOfThreads(int threads) { pipeline_.parameters().threads = threads; }
  int getNumberOfThreads() const { return pipeline_.parameters().threads; }
  /// Every matcher parameter at once (see lidar_sgm::Parameters); checked in filter().
  void setParameters(const Parameters& params) { pipeline_.setParameters(params); }
  const Parameters& getParameters() const { return pipeline_.parameters(); }
  void setBackend(Backend backend) { pipeline_.setBackend(backend); }

  /// Occlusion filter, depth range of the projected scan.
  void setProjectionOptions(const geometry::ProjectionOptions& options) { pipeline_.setProjectionOptions(options); }
  const geometry::ProjectionOptions& getProjectionOptions() const { return pipeline_.projectionOptions(); }

  /// LiDAR-only mode: no points above the scan's top or below its bottom beam, per column,
  /// where nothing was measured (default true).
  void setCropToScan(bool crop) { pipeline_.setCropToScan(crop); }
  bool getCropToScan() const { return pipeline_.cropToScan(); }

  void setKeepOrganized(bool keep) { pipeline_.reprojectionOptions().keepOrganized = keep; }
  bool getKeepOrganized() const { return pipeline_.reprojectionOptions().keepOrganized; }
  void setOutputFrame(geometry::OutputFrame frame) { pipeline_.reprojectionOptions().frame = frame; }
  geometry::OutputFrame getOutputFrame() const { return pipeline_.reprojectionOptions().frame; }
  void setCameraFrameId(const std::string& frameId) { cameraFrameId_ = frameId; }
  const std::string& getCameraFrameId() const { return cameraFrameId_; }
  /// Output points deeper than this [m] are dropped (default 80 m; infinity keeps all).
  void setMaxDepth(double maxDepth) { pipeline_.reprojectionOptions().maxDepth = maxDepth; }
  double getMaxDepth() const { return pipeline_.reprojectionOptions().maxDepth; }
  /// Every `stride`-th pixel in x and y (default 1).
  void setStride(int stride) { pipeline_.reprojectionOptions().stride = stride; }
  int getStride() const { return pipeline_.reprojectionOptions().stride; }

  /// Runs one frame. On error `output` is empty, PCL_ERROR says why, getLastError() too.
  void filter(PointCloudOut& output);

  /// The dense disparity of the last frame: x16 fixed point, kInvalidDisparity where none.
  const Image<std::int16_t>& getDisparityImage() const { return pipeline_.disparity(); }
  /// The dense depth of the last frame: z [m] in the left camera, 0 where none or beyond the
  /// max depth (KITTI depth completion's convention).
  const Image<float>& getDepthImage() const { return pipeline_.depth(); }
  /// The projected scan of the last frame (sparse disparities, per-reason counts).
  const geometry::ProjectedLidar& getProjectedLidar() const { return pipeline_.projected(); }
  const DensificationTimings& getTimings() const { return pipeline_.timings(); }
  MatchMode getLastMode() const { return pipeline_.lastMode(); }
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

  Densifier pipeline_;
  std::string className_ = "SGMDensification";
  std::string cameraFrameId_ = "camera_left_rect";
  std::string lastError_;
  std::string pendingError_;  ///< from a setter given unusable images, reported by filter()
  bool explicitColor_ = false;
};

}  // namespace lidar_sgm

#ifdef PCL_NO_PRECOMPILE
#include "lidar_sgm/pcl/impl/sgm_densification.hpp"
#endif
