#include "cloud_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/timer.hpp"
#include "lidar_sgm/eval/cloud_distance.hpp"
#include "lidar_sgm/eval/cloud_distance_report.hpp"
#include "lidar_sgm/io/atomic_file.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

namespace fs = std::filesystem;

/// The comma-separated numbers of `option` ("0,10,20"), or `fallback` when it is absent.
std::vector<double> numberList(const Arguments& args, const std::string& option, const std::string& fallback) {
  const std::string text = args.text(option, fallback);
  std::vector<double> numbers;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size()) {
      throw std::invalid_argument("option -" + option + ": '" + item + "' in '" + text + "' is not a number");
    }
    numbers.push_back(value);
  }
  if (numbers.empty()) throw std::invalid_argument("option -" + option + ": no value");
  return numbers;
}

/// x, y, z of a cloud file read by the project's readers (.pcd, .ply, KITTI .bin).
pcl::PointCloud<pcl::PointXYZ> loadCloud(const std::string& path, const char* what) {
  Timer timer;
  std::printf("Loading %s %s", what, path.c_str());
  std::fflush(stdout);
  const pcl::PointCloud<pcl::PointXYZI> read = io::readCloud(path);
  if (read.empty()) throw std::runtime_error(std::string("the ") + what + " '" + path + "' has no point");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(read.size());
  for (const pcl::PointXYZI& p : read) cloud.push_back(pcl::PointXYZ(p.x, p.y, p.z));
  std::printf(" [done, %.0f ms : %zu points]\n", timer.elapsedMs(), cloud.size());
  return cloud;
}

eval::CloudDistanceOptions optionsFrom(const Arguments& args) {
  eval::CloudDistanceOptions options;
  options.taus = numberList(args, "tau", "0.05");
  for (double tau : options.taus) {
    if (!(tau > 0.0 && std::isfinite(tau))) {
      throw std::invalid_argument("option -tau: " + args.text("tau", "") + " holds a value that is not > 0 [m]");
    }
  }
  const std::string bands = "0,10,20,40,80";
  options.bandEdges = args.text("bands", bands) == "none" ? std::vector<double>{} : numberList(args, "bands", bands);
  const std::vector<double> origin = numberList(args, "origin", "0,0,0");
  if (origin.size() != 3) throw std::invalid_argument("option -origin: '" + args.text("origin", "") + "' is not X,Y,Z");
  options.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]).cast<float>();
  const int threads = args.integer("threads", 0);
  if (threads < 0 || threads > 256) throw std::invalid_argument("option -threads: must be in [0, 256] (0 = all)");
  const unsigned hardware = std::thread::hardware_concurrency();
  options.threads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::min(hardware, 256u)));
  try {
    eval::validate(options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("option -bands: ") + e.what());  // the only check left
  }
  return options;
}

}  // namespace

std::set<std::string> cloudScoreOptions() { return {"cloud", "reference", "tau", "bands", "origin"}; }

std::string cloudScoreHelp() {
  return "  -cloud FILE         instead of the protocols: score this cloud (.pcd, .ply or KITTI .bin) in 3D against\n"
         "                      -reference FILE (a survey scan, a map, a synthetic scene's exact cloud), as\n"
         "                      reconstruction benchmarks do: precision = share of its points within tau of the\n"
         "                      reference, completeness = share of the reference's points within tau of it, F-score;\n"
         "                      overall and per range band. NaN points are skipped. Only -tau, -bands, -origin,\n"
         "                      -threads and -out go with it\n"
         "  -reference FILE     the reference cloud of -cloud\n"
         "  -tau T[,T...]       distance thresholds [m], each > 0 (default: 0.05)\n"
         "  -bands E,E,...      range band edges [m], increasing, or none (default: 0,10,20,40,80): a point's\n"
         "                      distance from -origin decides its band\n"
         "  -origin X,Y,Z       where ranges are measured from, in the clouds' frame (default: 0,0,0, the sensor)\n"
         "  (-out DIR writes DIR/cloud_distance.json; -threads N for the nearest-neighbour queries, 0 = all)\n";
}

int runCloudScore(const Arguments& args) {
  if (!args.has("cloud")) throw std::invalid_argument("option -reference: needs -cloud FILE, the cloud to score");
  if (!args.has("reference")) throw std::invalid_argument("option -cloud: needs -reference FILE, the cloud to score against");
  const std::set<std::string> allowed = joined(cloudScoreOptions(), {"out", "threads"});
  for (const auto& [name, value] : args.values()) {
    if (!allowed.count(name)) throw std::invalid_argument("option -" + name + ": not with -cloud (see -h)");
  }
  for (const std::string& name : args.flags()) throw std::invalid_argument("option -" + name + ": not with -cloud (see -h)");
  if (!args.positionals().empty()) {
    throw std::invalid_argument("unexpected argument '" + args.positionals().front() + "' (see -h)");
  }
  const eval::CloudDistanceOptions options = optionsFrom(args);
  const std::string cloudPath = args.text("cloud", "");
  const std::string referencePath = args.text("reference", "");
  const std::string out = args.text("out", "");
  const pcl::PointCloud<pcl::PointXYZ> cloud = loadCloud(cloudPath, "cloud");
  const pcl::PointCloud<pcl::PointXYZ> reference = loadCloud(referencePath, "reference");

  Timer timer;
  std::printf("Scoring against the reference (exact nearest neighbours, kd-tree, %d threads)", options.threads);
  std::fflush(stdout);
  const eval::CloudDistanceScore score = [&] {
    try {
      return eval::compareClouds(cloud, reference, options);
    } catch (const std::invalid_argument& e) {  // a cloud of NaN points only: name the file
      const bool aboutReference = std::string(e.what()).find("reference") != std::string::npos;
      throw std::runtime_error(std::string(e.what()) + " ('" + (aboutReference ? referencePath : cloudPath) + "')");
    }
  }();
  std::printf(" [done, %.0f ms]\n%s", timer.elapsedMs(), eval::cloudDistanceText(score).c_str());

  if (!out.empty()) {
    fs::create_directories(out);
    nlohmann::json json = eval::cloudDistanceJson(score);
    json["cloud"] = cloudPath;
    json["reference"] = referencePath;
    json["taus"] = options.taus;
    json["band_edges"] = options.bandEdges;
    json["origin"] = {options.origin.x(), options.origin.y(), options.origin.z()};
    const std::string path = (fs::path(out) / "cloud_distance.json").string();
    io::writeFileAtomically(path, json.dump(2));
    std::printf("Results in %s\n", path.c_str());
  }
  return 0;
}

}  // namespace apps
}  // namespace lidar_sgm
