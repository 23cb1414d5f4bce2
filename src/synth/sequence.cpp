// A drive along one street: the frames' rig positions and seeds, and the poses KITTI odometry writes.
#include "lidar_sgm/synth/sequence.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace synth {
namespace {

// Decorrelates the frames' noise streams (LiDAR, sensor, rain): an odd constant, so that
// seed + index * constant differs for every index below 2^32.
constexpr std::uint32_t kFrameSeedStride = 0x632BE5ABu;

void checkIndex(const SequenceOptions& options, int index) {
  if (index < 0 || index >= options.frames) {
    throw std::invalid_argument("frame index " + std::to_string(index) + " must be in [0, " +
                                std::to_string(options.frames) + ")");
  }
}

StereoRig rigOf(const SequenceOptions& options, int index) {
  StereoRig rig = StereoRig::kittiLike(options.frame.width, options.frame.height, options.frame.baseline);
  rig.origin = sequenceFrameOptions(options, index).rigPosition;
  return rig;
}

}  // namespace

void validate(const SequenceOptions& options) {
  if (options.frames < 1 || options.frames > 100000) {
    throw std::invalid_argument("sequence length " + std::to_string(options.frames) + " must be in [1, 100000] frames");
  }
  if (!(options.step > 0.0 && options.step <= 5.0)) {
    throw std::invalid_argument("step " + std::to_string(options.step) + " must be in (0, 5] m per frame");
  }
  if (!(options.period > 0.0 && options.period <= 10.0)) {
    throw std::invalid_argument("frame period " + std::to_string(options.period) + " must be in (0, 10] s");
  }
  FrameOptions frame = options.frame;
  frame.rigPosition = Eigen::Vector3d::Zero();
  validate(frame);
}

Scene makeSequenceScene(const SequenceOptions& options) {
  validate(options);
  return makeStreetScene(options.frame.seed, (options.frames - 1) * options.step);
}

FrameOptions sequenceFrameOptions(const SequenceOptions& options, int index) {
  validate(options);
  checkIndex(options, index);
  FrameOptions frame = options.frame;
  frame.seed = options.frame.seed + static_cast<std::uint32_t>(index) * kFrameSeedStride;
  frame.rigPosition = {index * options.step, 0.0, 0.0};
  return frame;
}

Frame renderSequenceFrame(const Scene& scene, const SequenceOptions& options, int index) {
  return renderFrame(scene, sequenceFrameOptions(options, index));
}

Frame renderSequenceFrame(const SequenceOptions& options, int index) {
  return renderSequenceFrame(makeSequenceScene(options), options, index);
}

Eigen::Isometry3d sequencePose(const SequenceOptions& options, int index) {
  checkIndex(options, index);
  return rigOf(options, 0).worldFromLeftCamera().inverse() * rigOf(options, index).worldFromLeftCamera();
}

Eigen::Isometry3d worldFromFirstCamera(const SequenceOptions& options) {
  return rigOf(options, 0).worldFromLeftCamera();
}

std::string kittiPosesText(const SequenceOptions& options) {
  validate(options);
  std::string text;
  char number[32];
  for (int i = 0; i < options.frames; ++i) {
    const Eigen::Matrix<double, 3, 4> m = sequencePose(options, i).matrix().topRows<3>();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        // An exact zero printed as 0: the rotation's products leave -0 and 1e-17-size noise otherwise.
        const double v = std::abs(m(r, c)) < 1e-15 ? 0.0 : m(r, c);
        std::snprintf(number, sizeof(number), "%.12e", v);
        if (r + c > 0) text += ' ';
        text += number;
      }
    }
    text += '\n';
  }
  return text;
}

std::string kittiTimesText(const SequenceOptions& options) {
  validate(options);
  std::string text;
  char number[32];
  for (int i = 0; i < options.frames; ++i) {
    std::snprintf(number, sizeof(number), "%.6e\n", i * options.period);
    text += number;
  }
  return text;
}

}  // namespace synth
}  // namespace lidar_sgm
