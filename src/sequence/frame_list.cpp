#include "lidar_sgm/sequence/frame_list.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "frame_folders.hpp"
#include "kitti2015_layout.hpp"
#include "lidar_sgm/io/file_access.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace {

using detail::framesOf;
using detail::isDirectory;
using detail::MissingScans;

bool isOdometrySequence(const fs::path& dir) { return isDirectory(dir / "velodyne") && fs::exists(dir / "calib.txt"); }

std::vector<Frame> odometrySequence(const fs::path& dir, const std::string& namePrefix) {
  const std::string calib = (dir / "calib.txt").string();
  return framesOf(dir / "velodyne", dir / "image_2", dir / "image_3", namePrefix, CalibrationFormat::KittiOdometry,
                  MissingScans::Reported, [&](const std::string&) { return calib; });
}

/// Every sequence of a `sequences` folder, in name order.
std::vector<Frame> odometrySequences(const fs::path& sequences) {
  std::vector<fs::path> folders;
  for (const fs::directory_entry& entry : fs::directory_iterator(sequences)) {
    if (entry.is_directory() && isOdometrySequence(entry.path())) folders.push_back(entry.path());
  }
  std::sort(folders.begin(), folders.end());
  std::vector<Frame> frames;
  for (const fs::path& folder : folders) {
    const std::vector<Frame> sequence = odometrySequence(folder, folder.filename().string() + "/");
    frames.insert(frames.end(), sequence.begin(), sequence.end());
  }
  return frames;
}

bool isRawDrive(const fs::path& dir) { return isDirectory(dir / "velodyne_points" / "data"); }

bool isObjectLayout(const fs::path& dir) { return isDirectory(dir / "velodyne") && isDirectory(dir / "calib"); }

std::vector<Frame> rawDrive(const fs::path& dir) {
  // The drive's calibration is the date folder's (calib_cam_to_cam.txt, calib_velo_to_cam.txt).
  const std::string calib = fs::absolute(dir).lexically_normal().parent_path().string();
  std::vector<Frame> frames = framesOf(dir / "velodyne_points" / "data", dir / "image_02" / "data",
                                       dir / "image_03" / "data", "", CalibrationFormat::Auto,
                                       MissingScans::Reported, [&](const std::string&) { return calib; });
  for (Frame& frame : frames) {
    frame.oxts = (dir / "oxts" / "data" / (fs::path(frame.scan).stem().string() + ".txt")).string();
  }
  return frames;
}

std::vector<Frame> framesOfLayout(const fs::path& dir) {
  switch (directoryLayout(dir.string())) {
    case Layout::KittiOdometrySequence:
      return odometrySequence(dir, "");
    case Layout::KittiRawDrive:
      return rawDrive(dir);
    case Layout::KittiObject:
      return framesOf(dir / "velodyne", dir / "image_2", dir / "image_3", "", CalibrationFormat::Auto,
                      MissingScans::Ignored, [&](const std::string& stem) { return (dir / "calib" / (stem + ".txt")).string(); });
    case Layout::KittiStereo2015:
      return detail::kittiStereo2015Frames(dir);
    case Layout::KittiOdometryRoot:
    case Layout::ListFile:
      break;
  }
  return odometrySequences(isDirectory(dir / "sequences") ? dir / "sequences" : dir);
}

/// A velodyne/ folder whose calibration is missing is no layout at all: say which files were
/// looked for beside it, the likeliest fault.
std::string calibrationHint(const fs::path& dir) {
  if (!isDirectory(dir / "velodyne")) return "";
  return ". It has velodyne/ but none of the calibrations looked for beside it: calib.txt (KITTI odometry), "
         "calib/ with calib/NNNNNN.txt per scan (KITTI object), calib/calib_cam_to_cam.txt with "
         "calib/calib_velo_to_cam.txt, or calib_cam_to_cam/ with calib_velo_to_cam/ (KITTI stereo 2015)";
}

}  // namespace

const char* layoutName(Layout layout) {
  switch (layout) {
    case Layout::KittiOdometrySequence: return "KITTI odometry sequence";
    case Layout::KittiOdometryRoot: return "KITTI odometry root";
    case Layout::KittiRawDrive: return "KITTI raw drive";
    case Layout::KittiObject: return "KITTI object layout";
    case Layout::KittiStereo2015: return "KITTI stereo 2015 training";
    case Layout::ListFile: return "list file";
  }
  return "unknown layout";
}

Layout directoryLayout(const std::string& dir) {
  const fs::path path(dir);
  if (isOdometrySequence(path)) return Layout::KittiOdometrySequence;
  if (isRawDrive(path)) return Layout::KittiRawDrive;
  // Before the object layout: KITTI 2015's shared calibration is in a calib/ folder too.
  if (detail::isKittiStereo2015(path)) return Layout::KittiStereo2015;
  if (isObjectLayout(path)) return Layout::KittiObject;
  return Layout::KittiOdometryRoot;
}

std::vector<Frame> framesFromDirectory(const std::string& dir) {
  if (!isDirectory(dir)) throw std::invalid_argument("-input_dir '" + dir + "' is not a folder");
  std::vector<Frame> frames = framesOfLayout(fs::path(dir));
  if (frames.empty()) {
    throw std::invalid_argument(
        "-input_dir '" + dir +
        "' has no frames: expected a KITTI odometry sequence (velodyne/, calib.txt, image_2/, image_3/), a KITTI "
        "odometry root (sequences/NN/), a KITTI raw drive (velodyne_points/data/, image_02/data/, image_03/data/), "
        "the KITTI object layout (velodyne/, calib/, image_2/, image_3/) or KITTI stereo 2015 training (velodyne/, "
        "image_2/, image_3/, calib/calib_cam_to_cam.txt or calib_cam_to_cam/), with .bin, .pcd or .ply scans" +
        calibrationHint(fs::path(dir)));
  }
  return frames;
}

std::vector<Frame> framesFromList(const std::string& listPath) {
  const std::string unreadable = io::unreadableFileReason(listPath);
  if (!unreadable.empty()) throw std::invalid_argument("cannot read the list file '" + listPath + "': " + unreadable);
  std::ifstream in(listPath);
  if (!in) throw std::invalid_argument("cannot read the list file '" + listPath + "'");
  const fs::path base = fs::path(listPath).parent_path();
  const auto resolve = [&](const std::string& field) -> std::string {
    if (field == "-") return "";
    const fs::path path(field);
    return path.is_absolute() ? field : (base / path).string();
  };
  std::vector<Frame> frames;
  std::set<std::string> names;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = "'" + listPath + "' line " + std::to_string(number);
    std::istringstream fields(line);
    std::vector<std::string> parts;
    for (std::string part; fields >> part;) parts.push_back(part);
    if (parts.empty() || parts[0][0] == '#') continue;
    if (parts.size() != 4) {
      throw std::invalid_argument(where + ": expected SCAN LEFT RIGHT CALIB ('-' for a missing image), got " +
                                  std::to_string(parts.size()) + " field(s)");
    }
    if (parts[0] == "-" || parts[3] == "-") throw std::invalid_argument(where + ": SCAN and CALIB are required");
    if (parts[1] == "-" && parts[2] != "-") throw std::invalid_argument(where + ": a RIGHT image needs a LEFT one");
    Frame frame;
    frame.scan = resolve(parts[0]);
    frame.left = resolve(parts[1]);
    frame.right = resolve(parts[2]);
    frame.calib = resolve(parts[3]);
    frame.name = fs::path(frame.scan).stem().string();
    if (!names.insert(frame.name).second) {
      throw std::invalid_argument(where + ": a second scan named '" + frame.name +
                                  "'; each frame's output is named after its scan");
    }
    frames.push_back(frame);
  }
  if (frames.empty()) throw std::invalid_argument("the list file '" + listPath + "' has no frames");
  return frames;
}

Shard parseShard(const std::string& text) {
  const std::size_t slash = text.find('/');
  Shard shard;
  try {
    std::size_t used = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    shard.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("trailing");
    shard.count = std::stoi(text.substr(slash + 1), &used);
    if (used != text.size() - slash - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw std::invalid_argument("option -shard: '" + text + "' is not K/N (e.g. 0/4)");
  }
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw std::invalid_argument("option -shard: '" + text + "' needs N >= 1 and 0 <= K < N");
  }
  return shard;
}

std::vector<Frame> framesOfShard(const std::vector<Frame>& frames, const Shard& shard) {
  std::vector<Frame> mine;
  for (std::size_t i = static_cast<std::size_t>(shard.index); i < frames.size();
       i += static_cast<std::size_t>(shard.count)) {
    mine.push_back(frames[i]);
  }
  return mine;
}

}  // namespace sequence
}  // namespace lidar_sgm
