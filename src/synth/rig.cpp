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

Vector3d StereoRig::lidarToCamera(const Vector3d& p) const {
  const Vector3d world = p + lidarOffset;  // relative to the left camera, world axes
  return {-world.y(), -world.z(), world.x()};
}

std::string kittiCalibrationText(const StereoRig& rig, bool withThirdCamera) {
  const double f = rig.focal;
  const double left[12] = {f, 0, rig.cx, 0, 0, f, rig.cy, 0, 0, 0, 1, 0};
  const double right[12] = {f, 0, rig.cx, -f * rig.baseline, 0, f, rig.cy, 0, 0, 0, 1, 0};
  // The third camera sits at y = -offset in the left camera's axes: P = K [I | -C].
  const double up[12] = {f, 0, rig.cx, 0, 0, f, rig.cy, f * rig.thirdCameraOffset, 0, 0, 1, 0};
  const double rect[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const Vector3d t = rig.lidarToCamera({0, 0, 0});
  const double velo[12] = {0, -1, 0, t.x(), 0, 0, -1, t.y(), 1, 0, 0, t.z()};
  const double imu[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::string text = matrixLine("P0:", left) + matrixLine("P1:", right) + matrixLine("P2:", left) +
                     matrixLine("P3:", right);
  std::string rectLine = "R0_rect:";
  char number[32];
  for (int i = 0; i < 9; ++i) {
    std::snprintf(number, sizeof(number), " %.12e", rect[i]);
    rectLine += number;
  }
  text += rectLine + "\n" + matrixLine("Tr_velo_to_cam:", velo) + matrixLine("Tr_imu_to_velo:", imu);
  if (withThirdCamera) text += matrixLine("P_up:", up);
  return text;
}

}  // namespace synth
}  // namespace lidar_sgm
