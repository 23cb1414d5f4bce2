#include "lidar_sgm/eval/ground_truth_cloud.hpp"

#include <stdexcept>
#include <vector>

namespace lidar_sgm {
namespace eval {
namespace {

pcl::PointCloud<pcl::PointXYZ> toPcl(const geometry::DenseCloud& cloud) {
  pcl::PointCloud<pcl::PointXYZ> out;
  out.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud.points) out.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return out;
}

const geometry::StereoCalibration& calibrationOf(const EvalFrame& frame) {
  if (!frame.calibration) {
    throw std::invalid_argument("GroundTruthCloud: frame " + frame.dataset + "/" + frame.name +
                                " has no calibration to reproject its ground truth with");
  }
  return *frame.calibration;
}

pcl::PointCloud<pcl::PointXYZ> groundTruthPoints(const EvalFrame& frame) {
  return toPcl(geometry::reproject(frame.groundTruth.view(), calibrationOf(frame), groundTruthCloudReprojection()));
}

}  // namespace

CloudDistanceOptions groundTruthCloudOptions() {
  CloudDistanceOptions options;
  options.taus = {0.1, kGroundTruthCloudTau, 0.5};
  options.bandEdges = {0.0, 10.0, 20.0, 40.0, 80.0};
  options.threads = 1;
  return options;
}

geometry::ReprojectionOptions groundTruthCloudReprojection() {
  geometry::ReprojectionOptions options;  // the tools' maxDepth, stride 1, unorganized
  options.frame = geometry::OutputFrame::Camera;
  return options;
}

GroundTruthCloud::GroundTruthCloud(const EvalFrame& frame) : frame_(frame), reference_(groundTruthPoints(frame)) {}

std::optional<CloudDistanceScore> GroundTruthCloud::score(ImageView<const std::int16_t> disparity) const {
  const geometry::DenseCloud cloud = geometry::reproject(disparity, calibrationOf(frame_), groundTruthCloudReprojection());
  if (cloud.size() == 0) return std::nullopt;
  std::vector<int> judged;
  judged.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (frame_.groundTruth(cloud.pixels[i].x, cloud.pixels[i].y) > 0.0f) judged.push_back(static_cast<int>(i));
  }
  return reference_.score(toPcl(cloud), judged, groundTruthCloudOptions());
}

}  // namespace eval
}  // namespace lidar_sgm
