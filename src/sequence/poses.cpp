#include "lidar_sgm/sequence/poses.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "number_line.hpp"
#include "lidar_sgm/sequence/oxts_poses.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace {

/// The 12 numbers of one line; `where` names the file and line in errors.
std::vector<double> numbersOf(const std::string& line, const std::string& where) {
  const std::vector<double> numbers = numbersOfLine(line, where);
  if (numbers.size() != 12) {
    throw std::invalid_argument(where + ": expected 12 numbers (a row-major 3x4 pose), got " +
                                std::to_string(numbers.size()));
  }
  return numbers;
}

Eigen::Isometry3d poseOf(const std::vector<double>& numbers, const std::string& where) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = numbers[static_cast<std::size_t>(4 * r + c)];
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthoError = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (orthoError > kPoseRotationTolerance || std::abs(det - 1.0) > kPoseRotationTolerance) {
    std::ostringstream message;
    message << where << ": not a rigid transform: its rotation has max |R^T R - I| = " << orthoError
            << ", det = " << det << " (tolerance " << kPoseRotationTolerance << ")";
    throw std::invalid_argument(message.str());
  }
  Eigen::Isometry3d pose;
  pose.matrix() = T;
  return pose;
}

bool isFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

}  // namespace

std::vector<Eigen::Isometry3d> readPoses(const std::string& path) {
  const std::string unreadable = io::unreadableFileReason(path);
  if (!unreadable.empty()) throw std::invalid_argument("cannot read the poses file '" + path + "': " + unreadable);
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read the poses file '" + path + "'");
  std::vector<Eigen::Isometry3d> poses;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = "poses file '" + path + "' line " + std::to_string(number);
    poses.push_back(poseOf(numbersOf(line, where), where));
  }
  if (poses.empty()) throw std::invalid_argument("the poses file '" + path + "' has no pose");
  return poses;
}

std::string findPosesFile(const std::vector<Frame>& frames) {
  std::set<fs::path> sequences;
  for (const Frame& frame : frames) {
    if (frame.calibFormat != CalibrationFormat::KittiOdometry) return "";
    sequences.insert(fs::path(frame.calib).parent_path());  // NN/calib.txt
  }
  if (sequences.size() > 1) {
    std::string names;
    for (const fs::path& sequence : sequences) names += (names.empty() ? "" : ", ") + sequence.filename().string();
    throw std::invalid_argument("the map is of one drive, but the frames are of " + std::to_string(sequences.size()) +
                                " KITTI odometry sequences (" + names + "): give -input_dir .../sequences/NN");
  }
  if (sequences.empty()) return "";
  const fs::path sequence = fs::absolute(*sequences.begin()).lexically_normal();
  const fs::path own = sequence / "poses.txt";
  if (isFile(own)) return own.string();
  // The dataset's layout: dataset/sequences/NN/ and dataset/poses/NN.txt.
  const fs::path dataset = sequence.parent_path().parent_path() / "poses" / (sequence.filename().string() + ".txt");
  return isFile(dataset) ? dataset.string() : "";
}

SequencePoses posesOfSequence(const std::vector<Frame>& frames, const std::string& posesPath) {
  const std::string found = findPosesFile(frames);  // also refuses frames of several sequences
  const std::string path = posesPath.empty() ? found : posesPath;
  const bool rawDrive = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                       [](const Frame& frame) { return !frame.oxts.empty(); });
  if (path.empty() && rawDrive) {
    try {
      return {oxtsPosesOfDrive(frames), "OXTS packets " + oxtsFolderOf(frames) +
                                            " (KITTI raw: the IMU's poses taken to the left camera)"};
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) +
                                  " (-map takes a KITTI raw drive's poses from oxts/data/ unless -poses FILE "
                                  "is given)");
    }
  }
  if (path.empty()) {
    throw std::invalid_argument(
        "-map needs the frames' poses: give -poses FILE (KITTI odometry format), or a KITTI odometry sequence "
        "with NN/poses.txt or the dataset's poses/NN.txt, or a KITTI raw drive with oxts/data/");
  }
  SequencePoses result{readPoses(path),
                       "poses file " + path + (posesPath.empty() ? " (found beside the sequence)" : " (-poses)")};
  if (result.poses.size() != frames.size()) {
    throw std::invalid_argument("the poses file '" + path + "' has " + std::to_string(result.poses.size()) +
                                " poses but the sequence has " + std::to_string(frames.size()) +
                                " frames: frame i takes line i");
  }
  return result;
}

}  // namespace sequence
}  // namespace lidar_sgm
