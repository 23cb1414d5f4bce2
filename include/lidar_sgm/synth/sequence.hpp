#pragma once
/// @file sequence.hpp  A synthetic drive: one street, the rig moving along it, KITTI odometry poses.
///
/// @code
///   lidar_sgm::synth::SequenceOptions options;   // 0.8 m a frame: ~29 km/h at KITTI's 10 Hz
///   options.frame.seed = 7;                      // the street
///   options.frames = 100;
///   const lidar_sgm::synth::Scene street = lidar_sgm::synth::makeSequenceScene(options);  // once
///   for (int i = 0; i < options.frames; ++i) {
///     const lidar_sgm::synth::Frame frame = lidar_sgm::synth::renderSequenceFrame(street, options, i);
///     const Eigen::Isometry3d pose = lidar_sgm::synth::sequencePose(options, i);  // camera i -> camera 0
///   }
/// @endcode
///
/// The car drives straight along the street's +x at `step` metres per frame, its rig standing at
/// world (index * step, 0, 0); the world is static (standing cars only), so every frame's exact
/// ground truth is the same scene seen from elsewhere.

#include <string>

#include <Eigen/Geometry>

#include "lidar_sgm/synth/frame.hpp"
#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {

struct SequenceOptions {
  FrameOptions frame;   ///< every frame's options; frame.seed picks the street, rigPosition is ignored
  int frames = 1;       ///< in [1, 100000]
  double step = 0.8;    ///< [m] driven between frames, in (0, 5]: 0.8 m is ~29 km/h at 10 Hz
  double period = 0.1;  ///< [s] between frames (KITTI's 10 Hz), written to times.txt
};

/// Throws std::invalid_argument naming the first bad option and its allowed values.
void validate(const SequenceOptions& options);

/// The street of the drive, long enough for the whole drive plus the sensors' range. Built once
/// and shared by the frames (renderSequenceFrame(scene, ...)). It follows from frame.seed and the
/// drive's length ((frames - 1) * step): a longer drive of the same seed is another street.
Scene makeSequenceScene(const SequenceOptions& options);

/// Frame `index`'s options: the rig at (index * step, 0, 0) and a seed of its own for the noise.
FrameOptions sequenceFrameOptions(const SequenceOptions& options, int index);

/// Frame `index` of the drive (0 <= index < frames, else std::invalid_argument). Deterministic:
/// the same options and index give the same frame, bit for bit, whether the scene was built once
/// for all frames or for this one.
Frame renderSequenceFrame(const Scene& scene, const SequenceOptions& options, int index);
Frame renderSequenceFrame(const SequenceOptions& options, int index);

/// Frame `index`'s left camera into frame 0's left camera, both in KITTI camera axes (x right,
/// y down, z forward): line `index` of KITTI odometry's poses.txt.
Eigen::Isometry3d sequencePose(const SequenceOptions& options, int index);

/// Frame 0's left camera (KITTI axes) into the scene's world frame: with sequencePose, a point
/// of any frame maps back into the scene, e.g. for Scene::distanceToSurface.
Eigen::Isometry3d worldFromFirstCamera(const SequenceOptions& options);

/// KITTI odometry poses.txt: one line per frame, the 3x4 row-major matrix of sequencePose.
std::string kittiPosesText(const SequenceOptions& options);

/// KITTI odometry times.txt: one line per frame, index * period in seconds.
std::string kittiTimesText(const SequenceOptions& options);

}  // namespace synth
}  // namespace lidar_sgm
