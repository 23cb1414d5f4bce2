#pragma once
// What the synth tests share: reading the calibration text back, and projecting the LiDAR with it.

#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "lidar_sgm/core/lidar_points.hpp"
#include "lidar_sgm/synth/frame.hpp"

namespace lidar_sgm {
namespace test {

/// Every "NAME: v v v ..." line of a KITTI calibration file.
inline std::map<std::string, std::vector<double>> parseCalibration(const std::string& text) {
  std::map<std::string, std::vector<double>> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::istringstream values(line.substr(colon + 1));
    std::vector<double> numbers;
    double v = 0;
    while (values >> v) numbers.push_back(v);
    rows[line.substr(0, colon)] = numbers;
  }
  return rows;
}

/// A LiDAR point in the left image through the written calibration: (u, v) and camera depth z.
struct Projection {
  double u = 0;
  double v = 0;
  double z = 0;
};

class CalibratedProjector {
 public:
  explicit CalibratedProjector(const std::string& calibrationText) {
    const auto rows = parseCalibration(calibrationText);
    p2_ = rows.at("P2");
    r0_ = rows.at("R0_rect");
    velo_ = rows.at("Tr_velo_to_cam");
  }
  double focal() const { return p2_[0]; }

  Projection project(const synth::LidarPoint& p) const {
    const double in[3] = {p.x, p.y, p.z};
    double cam[3];
    for (int r = 0; r < 3; ++r) {
      cam[r] = velo_[static_cast<std::size_t>(4 * r + 3)];
      for (int c = 0; c < 3; ++c) cam[r] += velo_[static_cast<std::size_t>(4 * r + c)] * in[c];
    }
    double rect[3];
    for (int r = 0; r < 3; ++r) {
      rect[r] = 0;
      for (int c = 0; c < 3; ++c) rect[r] += r0_[static_cast<std::size_t>(3 * r + c)] * cam[c];
    }
    double image[3];
    for (int r = 0; r < 3; ++r) {
      image[r] = p2_[static_cast<std::size_t>(4 * r + 3)];
      for (int c = 0; c < 3; ++c) image[r] += p2_[static_cast<std::size_t>(4 * r + c)] * rect[c];
    }
    return {image[0] / image[2], image[1] / image[2], rect[2]};
  }

 private:
  std::vector<double> p2_;
  std::vector<double> r0_;
  std::vector<double> velo_;
};

/// The frame's LiDAR as the matcher's input: d = f*b/z, several points per pixel allowed;
/// `inputMask` gets 1 where a point fell (those pixels are not scored).
inline LidarPoints lidarInput(const synth::Frame& frame, Image<std::uint8_t>& inputMask) {
  const CalibratedProjector projector(synth::kittiCalibrationText(frame.rig, false));
  const double focalBaseline = frame.rig.focal * frame.rig.baseline;
  std::vector<LidarSample> samples;
  inputMask = Image<std::uint8_t>(frame.rig.width, frame.rig.height, 0);
  for (const synth::LidarPoint& p : frame.lidar) {
    const Projection q = projector.project(p);
    if (q.z < 1.0) continue;
    const int x = static_cast<int>(std::lround(q.u));
    const int y = static_cast<int>(std::lround(q.v));
    if (x < 0 || y < 0 || x >= frame.rig.width || y >= frame.rig.height) continue;
    const long d16 = std::lround(focalBaseline / q.z * kDisparityScale);
    if (d16 <= 0) continue;
    samples.push_back({x, y, static_cast<int>(d16)});
    inputMask(x, y) = 1;
  }
  return LidarPoints(frame.rig.width, frame.rig.height, samples);
}

}  // namespace test
}  // namespace lidar_sgm
