#pragma once
// lidar_sgm_batch -map: the sequence's dense clouds, read back as written, brought into the world
// by their poses and merged into one voxel map, with a picture of it from above.

#include <cstddef>
#include <functional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "lidar_sgm/sequence/frame_list.hpp"
#include "common/arguments.hpp"
#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace apps {

/// -map OUT.pcd|.ply, -map_voxel (default 0.10 m), -map_picture (default OUT.png), -poses.
struct MapOptions {
  std::string mapPath;      ///< empty: no map
  std::string picturePath;
  std::string posesPath;    ///< empty: found beside a KITTI odometry sequence
  double voxelSize = 0.10;
};

std::set<std::string> mapValueOptions();
std::string mapOptionsHelp();

/// The options, checked before any frame is read (std::invalid_argument names the bad one):
/// -map's file type, -map_picture's (.png), -map_voxel > 0, the map options without -map, and
/// -map with a shard of several (the map needs every frame: run it after the shards, 0/1).
MapOptions mapOptionsFrom(const Arguments& args, const sequence::Shard& shard);

/// What the map's line of the summary says.
struct MapResult {
  bool ok = true;       ///< false when the map could not be built or written, or was stopped
  bool written = false; ///< the map and its picture were written
  std::string summary;  ///< "; map PATH: N points, X MB ..." for the summary line
};

/// The map of one sequence. Frames are announced as their clouds are complete (densified now
/// or skipped as done by an earlier run or another shard); build() then reads them back in
/// sequence order, so the map does not depend on the order frames finish in.
class SequenceMap {
 public:
  /// `frames`: the whole sequence, frame i taking pose i; `cloudFrame`: -frame; `width`,
  /// `height`: -image_size (0: from the calibration). Reads the poses now: throws
  /// std::invalid_argument for missing poses, a bad poses file or OXTS packet, a count other than
  /// the frame count, or frames of several odometry sequences.
  SequenceMap(const MapOptions& options, const std::vector<sequence::Frame>& frames, geometry::OutputFrame cloudFrame,
              int width, int height);

  /// `frame`'s cloud is complete at `cloudPath`. A frame never announced (failed, or not run)
  /// is left out of the map and reported by build().
  void frameWritten(const sequence::Frame& frame, const std::string& cloudPath);

  /// Builds and writes the map and its picture (atomically), reporting left-out frames and
  /// errors on stderr. Never throws: an error is in the result.
  /// `stop` is asked between frames and before the map is written: true stops the build, and
  /// nothing is written.
  MapResult build(const std::function<bool()>& stop = [] { return false; }) const;

  /// Where the poses came from, for the log.
  const std::string& posesSource() const { return posesSource_; }

 private:
  MapOptions options_;
  std::vector<sequence::Frame> frames_;
  std::vector<Eigen::Isometry3d> poses_;
  std::string posesSource_;
  std::vector<std::string> cloudPaths_;  ///< per frame; empty until announced
  std::unordered_map<std::string, std::size_t> indexOf_;  ///< frame name -> position in frames_
  geometry::OutputFrame cloudFrame_;
  int width_;
  int height_;
};

}  // namespace apps
}  // namespace lidar_sgm
