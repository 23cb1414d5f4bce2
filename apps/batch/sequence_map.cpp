#include "batch/sequence_map.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_to_world.hpp"
#include "lidar_sgm/sequence/map_cloud.hpp"
#include "batch/map_picture.hpp"
#include "lidar_sgm/sequence/poses.hpp"
#include "lidar_sgm/sequence/voxel_map.hpp"
#include "common/output_paths.hpp"
#include "common/timer.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace apps {
namespace {

/// The calibration's transforms of a frame, read once per calibration file.
struct FrameGeometry {
  geometry::StereoCalibration calibration;
  Eigen::Isometry3d poseCameraFromLidar;
};

std::string megabytes(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

/// A build stopped by a signal: nothing written, the caller says so.
MapResult stoppedResult() {
  MapResult result;
  result.ok = false;
  return result;
}

}  // namespace

std::set<std::string> mapValueOptions() { return {"map", "map_voxel", "map_picture", "poses"}; }

std::string mapOptionsHelp() {
  return "  -map OUT.pcd             also a merged map of the sequence (one sequence, no -shard K/N with N > 1):\n"
         "                           every frame's cloud as written, taken into frame 0's camera by its pose\n"
         "                           and merged into voxels (centroid, mean color and confidence); frames\n"
         "                           skipped as done are included, failed ones left out (reported)\n"
         "  -map_voxel M             the map's voxel size [m] (default: 0.10)\n"
         "  -map_picture FILE.png    the map seen from above, with the trajectory (default: OUT.png)\n"
         "  -poses FILE              the frames' poses, KITTI odometry format (a line per frame: row-major\n"
         "                           3x4 camera-to-world); default for a KITTI odometry sequence NN:\n"
         "                           NN/poses.txt, else the dataset's poses/NN.txt; for a KITTI raw drive:\n"
         "                           its OXTS packets oxts/data/*.txt (with the date's calib_imu_to_velo.txt)\n";
}

MapOptions mapOptionsFrom(const Arguments& args, const sequence::Shard& shard) {
  MapOptions options;
  if (!args.has("map")) {
    for (const char* name : {"map_voxel", "map_picture", "poses"}) {
      if (args.has(name)) throw std::invalid_argument(std::string("option -") + name + " needs -map OUT.pcd");
    }
    return options;
  }
  options.mapPath = args.text("map", "");
  try {
    io::checkCloudOutput(options.mapPath, io::CloudFormat::Binary);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -map: ") + e.what());
  }
  options.picturePath = args.text("map_picture", fs::path(options.mapPath).replace_extension(".png").string());
  if (lowerExtension(options.picturePath) != ".png") {
    throw std::invalid_argument("option -map_picture: '" + options.picturePath + "' must be a .png file");
  }
  options.voxelSize = args.number("map_voxel", options.voxelSize);
  if (!(options.voxelSize > 0.0) || !std::isfinite(options.voxelSize)) {
    throw std::invalid_argument("option -map_voxel: must be > 0 [m]");
  }
  options.posesPath = args.text("poses", "");
  if (shard.count > 1) {
    throw std::invalid_argument("option -map: the map needs every frame, but -shard " + std::to_string(shard.index) +
                                "/" + std::to_string(shard.count) +
                                " runs some: run the shards without -map, then once with -map (it skips the "
                                "frames done and builds the map)");
  }
  return options;
}

SequenceMap::SequenceMap(const MapOptions& options, const std::vector<sequence::Frame>& frames,
                         geometry::OutputFrame cloudFrame, int width, int height)
    : options_(options),
      frames_(frames),
      cloudPaths_(frames.size()),
      cloudFrame_(cloudFrame),
      width_(width),
      height_(height) {
  sequence::SequencePoses poses = sequence::posesOfSequence(frames, options.posesPath);
  poses_ = std::move(poses.poses);
  posesSource_ = std::move(poses.source);
  for (std::size_t i = 0; i < frames_.size(); ++i) indexOf_.emplace(frames_[i].name, i);
}

void SequenceMap::frameWritten(const sequence::Frame& frame, const std::string& cloudPath) {
  const auto found = indexOf_.find(frame.name);
  if (found == indexOf_.end()) throw std::logic_error("frame '" + frame.name + "' is not of the map's sequence");
  cloudPaths_[found->second] = cloudPath;
}

MapResult SequenceMap::build(const std::function<bool()>& stop) const {
  MapResult result;
  try {
    const Timer timer;
    sequence::VoxelMap map(options_.voxelSize);
    std::map<std::string, FrameGeometry> geometries;  // by calibration file
    std::vector<std::string> leftOut;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      if (stop()) return stoppedResult();
      const sequence::Frame& frame = frames_[i];
      if (cloudPaths_[i].empty()) {
        leftOut.push_back(frame.name);
        continue;
      }
      auto known = geometries.find(frame.calib);
      if (known == geometries.end()) {
        FrameGeometry geometry;
        geometry.calibration = sequence::readFrameCalibration(frame, width_, height_);
        geometry.poseCameraFromLidar = sequence::poseCameraFromLidar(frame, geometry.calibration);
        known = geometries.emplace(frame.calib, std::move(geometry)).first;
      }
      const FrameGeometry& g = known->second;
      map.add(sequence::readFrameCloud(cloudPaths_[i]), sequence::cloudToWorld(poses_[i], g.poseCameraFromLidar, g.calibration, cloudFrame_));
    }
    if (map.size() == 0) throw std::runtime_error("no frame's cloud to merge");
    if (stop()) return stoppedResult();
    sequence::writeMapCloud(options_.mapPath, map);
    std::vector<Eigen::Vector3d> trajectory;
    for (const Eigen::Isometry3d& pose : poses_) trajectory.push_back(pose.translation());
    TopViewOptions view;
    view.minMetresPerPixel = options_.voxelSize;
    const TopView top = renderTopView(map.points(), map.hasColor(), trajectory, view);
    io::writeImageAtomically(options_.picturePath, top.image);
    result.written = true;

    char text[512];
    std::snprintf(text, sizeof(text), "Map %s: %zu points, %s, %zu/%zu frames, voxel %.2f m, in %.1f s; picture %s",
                  options_.mapPath.c_str(), map.size(), megabytes(fs::file_size(options_.mapPath)).c_str(),
                  frames_.size() - leftOut.size(), frames_.size(), options_.voxelSize, timer.elapsedMs() / 1000.0,
                  options_.picturePath.c_str());
    result.summary = text;
    if (!leftOut.empty()) {
      std::string names;
      for (const std::string& name : leftOut) names += " " + name;
      std::fprintf(stderr, "Map: %zu frame(s) left out (failed or not run):%s\n", leftOut.size(), names.c_str());
      result.summary += " (" + std::to_string(leftOut.size()) + " frame(s) left out)";
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "Error: map %s: %s\n", options_.mapPath.c_str(), e.what());
    result.ok = false;
    result.summary = "Map not written (" + std::string(e.what()) + ")";
  }
  return result;
}

}  // namespace apps
}  // namespace lidar_sgm
