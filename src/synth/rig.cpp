#include "lidar_sgm/synth/rig.hpp"

#include <cstdio>

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

constexpr double kKittiWidth = 1242.0;
constexpr double kKittiHeight = 375.0;

PinholeCamera cameraAt(const StereoRig& rig, const Vector3d& position) {
  PinholeCamera c;
  c.position = position;
  c.width = rig.width;
  c.height = rig.height;
  c.focal = rig.focal;
  c.cx = rig.cx;
  c.cy = rig.cy;
  return c;
}

std::string matrixLine(const char* name, const double (&m)[12]) {
  std::string line = name;
  char number[32];
  for (double v : m) {
    std::snprintf(number, sizeof(number), " %.12e", v);
    line += number;
  }
  return line + "\n";
}

}  // namespace

StereoRig StereoRig::kittiLike(int width, int height, double baseline) {
  StereoRig rig;
  const double scaleX = width / kKittiWidth;
  rig.width = width;
  rig.height = height;
  rig.focal *= scaleX;
  rig.cx *= scaleX;
  rig.cy *= height / kKittiHeight;
  rig.baseline = baseline;
  return rig;
}

PinholeCamera StereoRig::left() const { return cameraAt(*this, leftPosition()); }
PinholeCamera StereoRig::right() const { return cameraAt(*this, leftPosition() + Vector3d{0.0, -baseline, 0.0}); }
PinholeCamera StereoRig::up() const { return cameraAt(*this, leftPosition() + Vector3d{0.0, 0.0, thirdCameraOffset}); }

Eigen::Isometry3d StereoRig::worldFromLeftCamera() const {
  Eigen::Matrix3d rotation;  // columns: the camera's x (right = -y world), y (down = -z), z (forward = +x)
  rotation << 0, 0, 1,
              -1, 0, 0,
              0, -1, 0;
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = rotation;
  transform.translation() = leftPosition();
  return transform;
}

Vector3d StereoRig::lidarToCamera(const Vector3d& p) const {
  const Vector3d world = p + lidarOffset;  // relative to the left camera, world axes
  return {-world.y(), -world.z(), world.x()};
}

namespace {

// P0..P3, the lines the object and the odometry formats share: this rig has no separate gray
// cameras, so P0 = P2 (left) and P1 = P3 (right).
std::string projectionLines(const StereoRig& rig) {
  const double f = rig.focal;
  const double left[12] = {f, 0, rig.cx, 0, 0, f, rig.cy, 0, 0, 0, 1, 0};
  const double right[12] = {f, 0, rig.cx, -f * rig.baseline, 0, f, rig.cy, 0, 0, 0, 1, 0};
  return matrixLine("P0:", left) + matrixLine("P1:", right) + matrixLine("P2:", left) + matrixLine("P3:", right);
}

// The third camera sits at y = -offset in the left camera's axes: P = K [I | -C].
std::string upLine(const StereoRig& rig) {
  const double f = rig.focal;
  const double up[12] = {f, 0, rig.cx, 0, 0, f, rig.cy, f * rig.thirdCameraOffset, 0, 0, 1, 0};
  return matrixLine("P_up:", up);
}

std::string lidarToCameraLine(const char* name, const StereoRig& rig) {
  const Vector3d t = rig.lidarToCamera({0, 0, 0});
  const double velo[12] = {0, -1, 0, t.x(), 0, 0, -1, t.y(), 1, 0, 0, t.z()};
  return matrixLine(name, velo);
}

}  // namespace

std::string kittiCalibrationText(const StereoRig& rig, bool withThirdCamera) {
  const double rect[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const double imu[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::string text = projectionLines(rig);
  std::string rectLine = "R0_rect:";
  char number[32];
  for (int i = 0; i < 9; ++i) {
    std::snprintf(number, sizeof(number), " %.12e", rect[i]);
    rectLine += number;
  }
  text += rectLine + "\n" + lidarToCameraLine("Tr_velo_to_cam:", rig) + matrixLine("Tr_imu_to_velo:", imu);
  if (withThirdCamera) text += upLine(rig);
  return text;
}

std::string kittiOdometryCalibrationText(const StereoRig& rig, bool withThirdCamera) {
  std::string text = projectionLines(rig) + lidarToCameraLine("Tr:", rig);
  if (withThirdCamera) text += upLine(rig);
  return text;
}

}  // namespace synth
}  // namespace lidar_sgm
