// The merged map checked against the truth: a synthetic drive (lidar_sgm_synth -sequence, whose
// scene is known exactly) densified and merged by lidar_sgm_batch -map, every map point measured
// against the nearest true surface of the scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "lidar_sgm/synth/scene.hpp"
#include "lidar_sgm/synth/sequence.hpp"
#include "common/run_command.hpp"
#include "common/test_paths.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

int shell(const std::string& command, std::string& output) {
  test::CommandResult result = test::runCommand(command);
  output += result.output;
  return result.exitCode;
}

/// Distances [m] from the map's points to the scene's surfaces, sorted.
std::vector<double> distancesToScene(const fs::path& mapPath, const synth::SequenceOptions& drive) {
  pcl::PointCloud<pcl::PointXYZ> map;
  EXPECT_EQ(pcl::io::loadPCDFile(mapPath.string(), map), 0) << mapPath;
  const synth::Scene scene = synth::makeSequenceScene(drive);
  const Eigen::Isometry3d worldFromMap = synth::worldFromFirstCamera(drive);  // the map is in camera 0
  std::vector<double> distances;
  distances.reserve(map.size());
  for (const pcl::PointXYZ& p : map) {
    distances.push_back(scene.distanceToSurface(worldFromMap * Eigen::Vector3d(p.x, p.y, p.z)));
  }
  std::sort(distances.begin(), distances.end());
  return distances;
}

double shareWithin(const std::vector<double>& sorted, double limit) {
  if (sorted.empty()) return 0.0;
  return static_cast<double>(std::upper_bound(sorted.begin(), sorted.end(), limit) - sorted.begin()) /
         static_cast<double>(sorted.size());
}

/// The merged map of a 4-frame synthetic drive made with `options`: distances of its points to the
/// true scene, sorted.
std::vector<double> mapDistances(const std::string& options) {
  const fs::path root = fs::temp_directory_path() / ("lidar_sgm_map_accuracy_" + std::to_string(getpid()));
  fs::remove_all(root);
  synth::SequenceOptions drive;
  drive.frame.seed = 3;
  drive.frames = 4;
  drive.step = 2.0;  // 4 frames over 6 m: most of the map is seen by several frames
  std::string log;
  EXPECT_EQ(shell(std::string(test::kSynthTool) + " -out " + (root / "seq").string() + " -sequence 4 -step 2 -seed 3 2>&1", log), 0) << log;
  EXPECT_EQ(shell(std::string(test::kBatchTool) + " -input_dir " + (root / "seq").string() + " -output_dir " +
                      (root / "out").string() + " -map " + (root / "map.pcd").string() + " " + options + " 2>&1",
                  log),
            0)
      << log;
  std::vector<double> d = distancesToScene(root / "map.pcd", drive);
  fs::remove_all(root);
  std::printf("%s: map points %zu; within 5 cm %.3f, 10 cm %.3f, 20 cm %.3f; median %.3f m, p95 %.3f m\n",
              options.c_str(), d.size(), shareWithin(d, 0.05), shareWithin(d, 0.10), shareWithin(d, 0.20),
              d.empty() ? 0.0 : d[d.size() / 2], d.empty() ? 0.0 : d[d.size() * 95 / 100]);
  return d;
}

TEST(MapAccuracy, NinetyFivePercentOfTheMergedMapLiesWithinTenCentimetresOfTheTrueScene) {
  // Stereo depth error grows with the square of the range (0.25 px is 6 cm at 10 m, 26 cm at 20 m
  // on this rig), so 10 cm is a fair bound for points up to 10 m from their camera; farther
  // points are measured in docs/RESULTS.md. LIDAR_SGM_MAP_ACCURACY_OPTIONS replaces the options
  // to measure others.
  if (const char* other = std::getenv("LIDAR_SGM_MAP_ACCURACY_OPTIONS")) {
    mapDistances(other);
    return;
  }
  // The map's own accuracy is measured without the hidden-LiDAR filter: the scene's LiDAR is
  // exact, and the points the filter leaves out here are mostly right ones (stereo's fattened
  // edges, vouched for by the object's own points), a cost checked separately below.
  const std::vector<double> d = mapDistances("-max_depth 10 -no_hidden_lidar_filter");
  ASSERT_GT(d.size(), 10000u);
  EXPECT_GE(shareWithin(d, 0.10), 0.95);
  EXPECT_LT(d[d.size() / 2], 0.02) << "the median point is on its surface";
  // With the defaults (the filter on) the share may drop by at most half a point (measured: 0.950 -> 0.947).
  const std::vector<double> withFilter = mapDistances("-max_depth 10");
  ASSERT_GT(withFilter.size(), 10000u);
  EXPECT_GE(shareWithin(withFilter, 0.10), shareWithin(d, 0.10) - 0.005);
  EXPECT_LT(withFilter[withFilter.size() / 2], 0.02);
}

}  // namespace
}  // namespace lidar_sgm
