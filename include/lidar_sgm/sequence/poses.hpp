#pragma once
// A sequence's poses in the KITTI odometry format, and where a sequence keeps them.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace sequence {

/// How far a pose's rotation may be from orthonormal (max |R^T R - I| entry, |det R - 1|): the
/// KITTI poses print about 7 digits, and drift over a long drive stays well inside this.
constexpr double kPoseRotationTolerance = 1e-3;

/// A KITTI odometry poses file: one line per frame, 12 numbers, the row-major 3x4 [R | t] that
/// takes frame i's camera coordinates to frame 0's (the world). Blank lines are not allowed
/// (line i is frame i). Throws std::invalid_argument naming the file and line for a line
/// without 12 numbers, a non-number, a non-finite number or a rotation that is not one (within
/// kPoseRotationTolerance), and for a file that cannot be read or has no line.
std::vector<Eigen::Isometry3d> readPoses(const std::string& path);

/// The poses file that belongs to `frames` when the command line gives none: for a KITTI
/// odometry sequence `.../sequences/NN/`, `NN/poses.txt` when it exists, else the dataset's
/// `.../poses/NN.txt` when it exists; "" when neither does or the frames are not one odometry
/// sequence. Throws std::invalid_argument when `frames` span several odometry sequences (the
/// map is of one drive).
std::string findPosesFile(const std::vector<Frame>& frames);

/// A sequence's poses and where they came from.
struct SequencePoses {
  std::vector<Eigen::Isometry3d> poses;  ///< frame i's is poses[i]
  std::string source;                    ///< for the log: "poses file X (-poses)", "OXTS packets of ..."
};

/// The poses of `frames`, frame i getting pose i: `posesPath` when given (-poses), else
/// findPosesFile(), else for a KITTI raw drive (frames with Frame::oxts) its OXTS packets
/// (oxtsPosesOfDrive). Throws std::invalid_argument when there is none of them or the poses
/// file's count is not the frame count, naming the file, and for a missing or bad OXTS packet.
SequencePoses posesOfSequence(const std::vector<Frame>& frames, const std::string& posesPath);

}  // namespace sequence
}  // namespace lidar_sgm
