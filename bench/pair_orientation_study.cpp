// pair_orientation_study: how clearly the pair check (pipeline/pair_orientation.hpp) tells a
// KITTI pair given as it is from the same pair swapped, and what it costs. For every frame of a
// KITTI 2015 layout with raw scans (velodyne/, image_2/, image_3/, calib/ with the raw date's
// calibration: ../shared/data/kitti2015_lidar), both orientations, both witnesses (the LiDAR
// points, the pair alone over [0, 128)): the votes, the verdict and the median time of -runs calls.
//   pair_orientation_study DIR [-runs N]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/arguments.hpp"
#include "common/tool_main.hpp"
#include "thread_cpu.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/io/kitti_bin.hpp"
#include "lidar_sgm/pipeline/pair_orientation.hpp"

namespace {

namespace fs = std::filesystem;
using lidar_sgm::PairOrientation;

using lidar_sgm::bench::medianOf;
using lidar_sgm::bench::threadCpuMs;

/// The share of the tested patches that voted `wins`, in percent.
double share(std::size_t wins, const PairOrientation& v) {
  return v.tested ? 100.0 * static_cast<double>(wins) / static_cast<double>(v.tested) : 0.0;
}

struct Range {
  double low = 1e9;
  double high = -1e9;
  void add(double v) {
    low = std::min(low, v);
    high = std::max(high, v);
  }
};

int run(int argc, char** argv) {
  const lidar_sgm::apps::Arguments args(argc, argv, {"runs"}, {});
  if (args.positionals().size() != 1) throw std::invalid_argument("expected DIR (a KITTI 2015 layout with velodyne/)");
  const int runs = args.integer("runs", 5);
  if (runs < 1) throw std::invalid_argument("option -runs: must be >= 1");
  const fs::path dir = args.positionals()[0];
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir / "velodyne")) names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  if (names.empty()) throw std::invalid_argument("no scan in '" + (dir / "velodyne").string() + "'");
  lidar_sgm::geometry::StereoCalibration calibration = lidar_sgm::io::readCalibration((dir / "calib").string());

  // [orientation][witness]: the share voting "as given" and "swapped", refusals, times.
  Range given[2][2];
  Range swapped[2][2];
  int refused[2][2] = {};
  std::vector<double> ms[2];
  for (const std::string& name : names) {
    const std::vector<lidar_sgm::io::KittiPoint> scan =
        lidar_sgm::io::readKittiScan((dir / "velodyne" / (name + ".bin")).string());
    std::vector<Eigen::Vector3f> points;
    for (const auto& p : scan) points.emplace_back(p.x, p.y, p.z);
    const cv::Mat left = lidar_sgm::io::readGrayImage((dir / "image_2" / (name + ".png")).string());
    const cv::Mat right = lidar_sgm::io::readGrayImage((dir / "image_3" / (name + ".png")).string());
    calibration.width = left.cols;
    calibration.height = left.rows;
    const std::vector<lidar_sgm::LidarSample> samples =
        lidar_sgm::geometry::project(points, calibration, lidar_sgm::geometry::ProjectionOptions()).samples;
    for (int orientation = 0; orientation < 2; ++orientation) {
      const lidar_sgm::GrayImageView l = lidar_sgm::io::grayView(orientation == 0 ? left : right);
      const lidar_sgm::GrayImageView r = lidar_sgm::io::grayView(orientation == 0 ? right : left);
      for (int witness = 0; witness < 2; ++witness) {
        std::vector<double> times;
        PairOrientation votes;
        for (int i = 0; i < runs; ++i) {
          const double start = threadCpuMs();
          votes = witness == 0 ? lidar_sgm::pairOrientationFromLidar(l, r, samples)
                               : lidar_sgm::pairOrientationFromStereo(l, r, 0, 128);
          times.push_back(threadCpuMs() - start);
        }
        if (orientation == 0) ms[witness].push_back(medianOf(times));
        given[orientation][witness].add(share(votes.givenWins, votes));
        swapped[orientation][witness].add(share(votes.swappedWins, votes));
        refused[orientation][witness] += votes.looksSwapped() ? 1 : 0;
      }
    }
  }
  const char* witnesses[2] = {"LiDAR points", "pair alone  "};
  const char* orientations[2] = {"as given", "swapped "};
  std::printf("%zu frames of %s, %d runs per check\n", names.size(), dir.string().c_str(), runs);
  for (int o = 0; o < 2; ++o) {
    for (int w = 0; w < 2; ++w) {
      std::printf("%s, %s: refused %2d of %zu; votes as given %5.1f-%5.1f %%, swapped %5.1f-%5.1f %% of the tested\n",
                  orientations[o], witnesses[w], refused[o][w], names.size(), given[o][w].low, given[o][w].high,
                  swapped[o][w].low, swapped[o][w].high);
    }
  }
  for (int w = 0; w < 2; ++w) {
    std::printf("time, %s: median %.2f ms thread CPU per frame (max %.2f)\n", witnesses[w], medianOf(ms[w]),
                *std::max_element(ms[w].begin(), ms[w].end()));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return lidar_sgm::apps::runTool(run, argc, argv); }
