#include "lidar_sgm/synth/frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {
namespace {

// Independent streams for the parts of a frame, so that e.g. rain never changes the LiDAR.
constexpr std::uint32_t kLidarStream = 0x9E3779B9u;
constexpr std::uint32_t kLeftStream = 0x85EBCA6Bu;
constexpr std::uint32_t kRightStream = 0xC2B2AE35u;
constexpr std::uint32_t kUpStream = 0x27D4EB2Fu;

}  // namespace

void validate(const FrameOptions& o) {
  if (o.beams != 64 && o.beams != 128) {
    throw std::invalid_argument("beams " + std::to_string(o.beams) + " must be 64 or 128");
  }
  if (!(o.baseline >= 0.05 && o.baseline <= 2.0)) {
    throw std::invalid_argument("baseline " + std::to_string(o.baseline) + " must be in [0.05, 2] m");
  }
  if (o.width < 32 || o.width > 4096 || o.height < 32 || o.height > 4096) {
    throw std::invalid_argument("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                " must be in [32, 4096] x [32, 4096]");
  }
  if (!(o.lidarRangeNoise >= 0.0 && o.lidarRangeNoise <= 1.0)) {
    throw std::invalid_argument("LiDAR range noise " + std::to_string(o.lidarRangeNoise) + " must be in [0, 1] m");
  }
  const Eigen::Vector3d& p = o.rigPosition;
  if (!(std::isfinite(p.x()) && std::abs(p.x()) < 1e6 && std::abs(p.y()) <= 1.0 && p.z() == 0.0)) {
    throw std::invalid_argument("rig position (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
                                std::to_string(p.z()) + ") must be on the road in the ego lane: |x| < 1e6, " +
                                "|y| <= 1, z = 0 m");
  }
}

Frame renderFrame(const FrameOptions& options) {
  validate(options);
  return renderFrame(makeStreetScene(options.seed), options);
}

Frame renderFrame(const Scene& scene, const FrameOptions& options) {
  validate(options);
  Frame frame;
  frame.rig = StereoRig::kittiLike(options.width, options.height, options.baseline);
  frame.rig.origin = options.rigPosition;
  RenderedView left = renderView(scene, frame.rig.left(), options.weather, options.seed ^ kLeftStream);
  frame.left = std::move(left.color);
  frame.depth = std::move(left.depth);
  frame.objectMask = std::move(left.objectMask);
  frame.right = renderView(scene, frame.rig.right(), options.weather, options.seed ^ kRightStream).color;
  if (options.thirdCamera) frame.up = renderView(scene, frame.rig.up(), options.weather, options.seed ^ kUpStream).color;
  frame.disparity.resize(options.width, options.height);
  const double focalBaseline = frame.rig.focal * frame.rig.baseline;
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      const float z = frame.depth(x, y);
      frame.disparity(x, y) = z > 0.0f ? static_cast<float>(focalBaseline / z) : 0.0f;
    }
  }
  LidarOptions lidar = LidarOptions::forBeams(options.beams);
  lidar.rangeNoiseSigma = options.lidarRangeNoise;
  frame.lidar = scanLidar(scene, frame.rig.lidarPosition(), lidar, options.seed ^ kLidarStream);
  if (options.lidarInCameraViewOnly) frame.lidar = keepInCameraView(frame.lidar, frame.rig);
  return frame;
}

namespace {

// The left-image pixel (u, v) and camera depth z of a LiDAR point; false when behind the camera
// or outside the image.
bool projectToLeft(const LidarPoint& p, const StereoRig& rig, double& u, double& v, double& z) {
  const Eigen::Vector3d c = rig.lidarToCamera({p.x, p.y, p.z});
  if (c.z() <= 0.1) return false;
  u = rig.focal * c.x() / c.z() + rig.cx;
  v = rig.focal * c.y() / c.z() + rig.cy;
  z = c.z();
  return u > -0.5 && u < rig.width - 0.5 && v > -0.5 && v < rig.height - 0.5;
}

}  // namespace

std::vector<LidarPoint> keepInCameraView(const std::vector<LidarPoint>& points, const StereoRig& rig) {
  std::vector<LidarPoint> kept;
  double u = 0, v = 0, z = 0;
  for (const LidarPoint& p : points) {
    if (projectToLeft(p, rig, u, v, z)) kept.push_back(p);
  }
  return kept;
}

Image<float> projectLidarDisparity(const std::vector<LidarPoint>& points, const StereoRig& rig) {
  Image<float> disparity(rig.width, rig.height, 0.0f);
  double u = 0, v = 0, z = 0;
  for (const LidarPoint& p : points) {
    if (!projectToLeft(p, rig, u, v, z)) continue;
    const float d = static_cast<float>(rig.focal * rig.baseline / z);  // Eq. 3
    float& pixel = disparity(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v)));
    pixel = std::max(pixel, d);  // the nearest point wins, as in KITTI's projected scans
  }
  return disparity;
}

}  // namespace synth
}  // namespace lidar_sgm
