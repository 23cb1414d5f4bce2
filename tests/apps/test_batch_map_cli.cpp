// lidar_sgm_batch -map as a user runs it, on a tiny sequence rendered by lidar_sgm_synth with
// hand-written poses: the map and its picture, their poses found or given (a KITTI raw drive's
// from its OXTS packets), re-runs that only build the map, and the refusals.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>

#include "lidar_sgm/sequence/frame_list.hpp"
#include "batch/sequence_map.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/pcl/point_types.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult shell(const std::string& command) {
  return test::runCommand(command);
}

RunResult batch(const std::string& arguments) {
  return shell(std::string(test::kBatchTool) + " " + arguments + " 2>&1");
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The mean position of a map's points.
Eigen::Vector3d meanOf(const fs::path& map) {
  pcl::PointCloud<PointXYZRGBConfidence> cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(map.string(), cloud), 0) << map;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const PointXYZRGBConfidence& p : cloud) sum += Eigen::Vector3d(p.x, p.y, p.z);
  return sum / static_cast<double>(cloud.size());
}

constexpr int kFrames = 3;

/// A pose per frame: frame i at (0, 0, step * i) (driving forward), KITTI odometry format.
std::string forwardPoses(double step, int frames = kFrames) {
  std::string text;
  for (int i = 0; i < frames; ++i) text += "1 0 0 0 0 1 0 0 0 0 1 " + std::to_string(step * i) + "\n";
  return text;
}

/// The number of points of a map.
std::size_t sizeOf(const fs::path& map) {
  pcl::PCLPointCloud2 cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(map.string(), cloud), 0) << map;
  return static_cast<std::size_t>(cloud.width) * cloud.height;
}

/// The value of `key` in a KITTI calibration text ("KEY: values").
std::string valueOf(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\n" + key + ":");
  EXPECT_NE(at, std::string::npos) << key;
  const std::size_t begin = at + key.size() + 2;
  return text.substr(begin, text.find('\n', begin) - begin);
}

/// An OXTS packet line of the IMU pose `imu` in the world of a drive whose first packet is at
/// latitude `lat0`, longitude `lon0`, altitude `alt0` (the east-north-up metres of the KITTI raw
/// devkit's Mercator projection inverted; roll, pitch, yaw from the rotation Rz * Ry * Rx).
std::string packetOf(const Eigen::Isometry3d& imu, double lat0, double lon0, double alt0) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr double kEarthRadius = 6378137.0;
  const double sr = std::cos(lat0 * kPi / 180.0) * kEarthRadius;
  const double x = sr * lon0 * kPi / 180.0 + imu.translation().x();
  const double y = sr * std::log(std::tan((90.0 + lat0) * kPi / 360.0)) + imu.translation().y();
  const Eigen::Vector3d yawPitchRoll = imu.linear().eulerAngles(2, 1, 0);
  char text[512];
  std::snprintf(text, sizeof(text),
                "%.17g %.17g %.17g %.17g %.17g %.17g 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0.5 0.05 4 10 4 4 6\n",
                std::atan(std::exp(y / sr)) * 360.0 / kPi - 90.0, x / sr * 180.0 / kPi, alt0 + imu.translation().z(),
                yawPitchRoll[2], yawPitchRoll[1], yawPitchRoll[0]);
  return text;
}

class BatchMap : public ::testing::Test {
 protected:
  /// kFrames frames of 320x96, rendered once for the suite, as a KITTI odometry dataset
  /// dataset/sequences/00 (calib.txt: the object calibration with R0_rect = I folded into Tr).
  static void SetUpTestSuite() {
    synth_ = fs::temp_directory_path() / ("lidar_sgm_batch_map_synth_" + std::to_string(getpid()));
    fs::remove_all(synth_);
    const RunResult r = shell(std::string(test::kSynthTool) + " -out " + (synth_ / "object").string() + " -n " +
                              std::to_string(kFrames) + " -width 320 -height 96 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path seq = synth_ / "dataset" / "sequences" / "00";
    for (const char* folder : {"velodyne", "image_2", "image_3"}) {
      fs::create_directories(seq / folder);
      for (const fs::directory_entry& e : fs::directory_iterator(synth_ / "object" / folder)) {
        fs::copy_file(e.path(), seq / folder / e.path().filename());
      }
    }
    std::ifstream object(synth_ / "object" / "calib" / "000000.txt");
    std::ofstream calib(seq / "calib.txt");
    for (std::string line; std::getline(object, line);) {
      if (line.rfind("R0_rect:", 0) == 0) continue;  // the identity (synth's rig is rectified)
      calib << (line.rfind("Tr_velo_to_cam:", 0) == 0 ? "Tr:" + line.substr(15) : line) << '\n';
    }
  }
  static void TearDownTestSuite() { fs::remove_all(synth_); }

  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("lidar_sgm_batch_map_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
             "_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  /// A copy of the sequence with `poses` as its poses.txt (none when empty).
  fs::path sequenceWith(const std::string& poses) {
    const fs::path seq = root_ / "seq" / "00";
    fs::create_directories(seq.parent_path());
    fs::copy(synth_ / "dataset" / "sequences" / "00", seq, fs::copy_options::recursive);
    if (!poses.empty()) std::ofstream(seq / "poses.txt") << poses;
    return seq;
  }
  static fs::path datasetSequence() { return synth_ / "dataset" / "sequences" / "00"; }

  static fs::path synth_;
  fs::path root_;
};

fs::path BatchMap::synth_;

TEST_F(BatchMap, SequenceWithPosesGivesAMapAndItsPictureAndAReRunThatSkipsEveryFrameTheSameBytes) {
  const fs::path seq = sequenceWith(forwardPoses(2.0));
  const fs::path out = root_ / "out";
  const fs::path map = root_ / "map.pcd";
  const std::string line = "-input_dir " + seq.string() + " -output_dir " + out.string() + " -map " + map.string();
  RunResult r = batch(line);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("3 ok, 0 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Map " + map.string() + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" points, "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" MB, 3/3 frames, voxel 0.10 m"), std::string::npos) << r.output;
  const std::string mapBytes = readText(map);
  const std::string pictureBytes = readText(root_ / "map.png");
  EXPECT_NE(mapBytes.find("FIELDS x y z rgb confidence"), std::string::npos);
  EXPECT_NE(mapBytes.find("DATA binary\n"), std::string::npos);
  EXPECT_EQ(pictureBytes.rfind("\x89PNG", 0), 0u) << "the picture from above is a PNG next to the map";

  // The map's points are fewer than the frames' (merged into voxels), none lost.
  pcl::PointCloud<PointXYZRGBConfidence> merged;
  ASSERT_EQ(pcl::io::loadPCDFile(map.string(), merged), 0);
  std::size_t framePoints = 0;
  for (int i = 0; i < kFrames; ++i) {
    pcl::PCLPointCloud2 frame;
    ASSERT_EQ(pcl::io::loadPCDFile((out / ("00000" + std::to_string(i) + ".pcd")).string(), frame), 0);
    framePoints += frame.width * frame.height;
  }
  EXPECT_GT(merged.size(), 1000u);
  EXPECT_LT(merged.size(), framePoints);

  r = batch(line);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 3 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_TRUE(readText(map) == mapBytes) << "the re-run's map differs";
  EXPECT_TRUE(readText(root_ / "map.png") == pictureBytes) << "the re-run's picture differs";
}

TEST_F(BatchMap, AKilledRunsMapTemporariesAreRemovedAndAStoppedBuildWritesNothing) {
  const fs::path seq = sequenceWith(forwardPoses(2.0));
  const fs::path out = root_ / "out";
  const fs::path map = root_ / "map.pcd";
  // As kill -9 during the map's write leaves them: its writer's pid no longer lives.
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  const std::string dead = ".tmp" + std::to_string(child);
  for (const char* extension : {".pcd", ".png"}) std::ofstream(root_ / (".map" + dead + extension)) << "half a map";
  RunResult r = batch("-input_dir " + seq.string() + " -output_dir " + out.string() + " -map " + map.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("(removed 2 temporary file(s) an interrupted run left)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(root_ / (".map" + dead + ".pcd")));
  EXPECT_FALSE(fs::exists(root_ / (".map" + dead + ".png")));

  // A stop asked during the build (SIGTERM, SIGINT) writes neither the map nor its picture.
  apps::MapOptions options;
  options.mapPath = (root_ / "stopped.pcd").string();
  options.picturePath = (root_ / "stopped.png").string();
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(seq.string());
  for (int stopAfter : {0, 2, kFrames}) {  // at once, between frames, just before the write
    apps::SequenceMap sequence(options, frames, geometry::OutputFrame::Lidar, 0, 0);
    for (const sequence::Frame& frame : frames) sequence.frameWritten(frame, (out / (frame.name + ".pcd")).string());
    int asked = 0;
    const apps::MapResult result = sequence.build([&] { return asked++ >= stopAfter; });
    EXPECT_FALSE(result.ok);
    EXPECT_FALSE(result.written);
    EXPECT_FALSE(fs::exists(options.mapPath)) << stopAfter;
    EXPECT_FALSE(fs::exists(options.picturePath)) << stopAfter;
  }
}

TEST_F(BatchMap, ThePosesMoveTheMapAndTheCloudsFrameDoesNot) {
  // One densification (poses found in the dataset's poses/00.txt), then maps built from its clouds
  // by re-runs that skip every frame.
  const fs::path dataset = root_ / "dataset";
  fs::create_directories(dataset / "sequences");
  fs::copy(datasetSequence(), dataset / "sequences" / "00", fs::copy_options::recursive);
  fs::create_directories(dataset / "poses");
  std::ofstream(dataset / "poses" / "00.txt") << forwardPoses(0.0);
  const std::string input = "-input_dir " + (dataset / "sequences" / "00").string();
  const fs::path out = root_ / "out";
  RunResult r = batch(input + " -output_dir " + out.string() + " -map " + (root_ / "still.pcd").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;

  // Every pose 5 m further forward and 1 m right: the whole map moves by as much.
  std::string moved;
  for (int i = 0; i < kFrames; ++i) moved += "1 0 0 1 0 1 0 0 0 0 1 5\n";
  std::ofstream(root_ / "moved.txt") << moved;
  r = batch(input + " -output_dir " + out.string() + " -map " + (root_ / "moved.pcd").string() + " -poses " +
            (root_ / "moved.txt").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Eigen::Vector3d shift = meanOf(root_ / "moved.pcd") - meanOf(root_ / "still.pcd");
  EXPECT_LT((shift - Eigen::Vector3d(1, 0, 5)).norm(), 0.02) << shift.transpose();

  // Clouds written in the camera frame give the same map, within the voxels' rounding.
  const fs::path cameraOut = root_ / "camera";
  r = batch(input + " -output_dir " + cameraOut.string() + " -frame camera -map " + (root_ / "camera.pcd").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Eigen::Vector3d difference = meanOf(root_ / "camera.pcd") - meanOf(root_ / "still.pcd");
  EXPECT_LT(difference.norm(), 0.02) << difference.transpose();
}

TEST_F(BatchMap, AFailedFrameIsLeftOutAndReported) {
  const fs::path seq = sequenceWith(forwardPoses(1.0));
  std::ofstream(seq / "velodyne" / "000001.bin", std::ios::binary | std::ios::trunc) << "truncated";
  const fs::path map = root_ / "map.pcd";
  const RunResult r =
      batch("-input_dir " + seq.string() + " -output_dir " + (root_ / "out").string() + " -map " + map.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("Map: 1 frame(s) left out (failed or not run): 000001"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2/3 frames"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(map));
}

TEST_F(BatchMap, AListFileTakesItsPosesFromPoses) {
  const fs::path object = synth_ / "object";
  std::ofstream list(root_ / "frames.txt");
  for (int i = 0; i < 2; ++i) {
    const std::string stem = "00000" + std::to_string(i);
    list << object.string() << "/velodyne/" << stem << ".bin " << object.string() << "/image_2/" << stem << ".png "
         << object.string() << "/image_3/" << stem << ".png " << object.string() << "/calib/" << stem << ".txt\n";
  }
  list.close();
  std::ofstream(root_ / "poses.txt") << forwardPoses(3.0, 2);
  const std::string base = "-list " + (root_ / "frames.txt").string() + " -output_dir " + (root_ / "out").string() +
                           " -map " + (root_ / "map.pcd").string() + " -map_picture " + (root_ / "top.png").string();
  RunResult r = batch(base);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("-map needs the frames' poses: give -poses FILE"), std::string::npos) << r.output;
  r = batch(base + " -poses " + (root_ / "poses.txt").string() + " -map_voxel 0.5");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2/2 frames, voxel 0.50 m"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(root_ / "top.png"));
}

TEST_F(BatchMap, AKittiRawDriveTakesItsPosesFromItsOxtsPackets) {
  // The synthetic frames as a KITTI raw drive: the date folder's calibration made of the object
  // calibration, an IMU behind and below the LiDAR, and OXTS packets of a vehicle heading north-east
  // whose left camera moves as forwardPoses(2.0) says.
  const fs::path object = synth_ / "object";
  const fs::path date = root_ / "2011_09_26";
  const fs::path drive = date / "2011_09_26_drive_0001_sync";
  for (const auto& [from, to] : {std::pair<const char*, const char*>{"velodyne", "velodyne_points"},
                                 {"image_2", "image_02"},
                                 {"image_3", "image_03"}}) {
    fs::create_directories(drive / to / "data");
    for (const fs::directory_entry& e : fs::directory_iterator(object / from)) {
      fs::copy_file(e.path(), drive / to / "data" / ("0000" + e.path().filename().string()));
    }
  }
  const std::string calib = "\n" + readText(object / "calib" / "000000.txt");
  std::istringstream tr(valueOf(calib, "Tr_velo_to_cam"));
  std::vector<double> t(12);
  for (double& v : t) tr >> v;
  std::ofstream(date / "calib_cam_to_cam.txt") << "calib_time: 09-Jan-2012 13:57:47\nP_rect_02:" << valueOf(calib, "P2")
                                                << "\nP_rect_03:" << valueOf(calib, "P3")
                                                << "\nR_rect_00:" << valueOf(calib, "R0_rect")
                                                << "\nS_rect_02: 3.200000e+02 9.600000e+01\n";
  std::ofstream veloToCam(date / "calib_velo_to_cam.txt");
  veloToCam.precision(17);
  veloToCam << "R: " << t[0] << " " << t[1] << " " << t[2] << " " << t[4] << " "
            << t[5] << " " << t[6] << " " << t[8] << " " << t[9] << " " << t[10] << "\nT: " << t[3] << " " << t[7]
            << " " << t[11] << "\n";
  veloToCam.close();
  Eigen::Isometry3d lidarFromImu = Eigen::Isometry3d::Identity();
  lidarFromImu.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  lidarFromImu.translation() = Eigen::Vector3d(-0.81, 0.32, -0.8);
  char imuToVelo[256];
  const Eigen::Matrix3d& R = lidarFromImu.linear();
  std::snprintf(imuToVelo, sizeof(imuToVelo), "R: %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\nT: -0.81 0.32 -0.8\n",
                R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  std::ofstream(date / "calib_imu_to_velo.txt") << imuToVelo;
  const Eigen::Isometry3d cameraFromImu = io::readCalibration(date.string()).T_cam_lidar * lidarFromImu;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();  // heading 0.7 rad north of east, pitched
  start.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()))
                       .toRotationMatrix();
  fs::create_directories(drive / "oxts" / "data");
  for (int i = 0; i < kFrames; ++i) {
    Eigen::Isometry3d camera = Eigen::Isometry3d::Identity();
    camera.translation() = Eigen::Vector3d(0, 0, 2.0 * i);
    const Eigen::Isometry3d imu = start * cameraFromImu.inverse() * camera * cameraFromImu;
    std::ofstream(drive / "oxts" / "data" / ("000000000" + std::to_string(i) + ".txt"))
        << packetOf(imu, 49.011, 8.423, 112.9);
  }
  std::ofstream(root_ / "forward.txt") << forwardPoses(2.0);
  std::ofstream(root_ / "still.txt") << forwardPoses(0.0);

  const std::string base = "-input_dir " + drive.string() + " -output_dir " + (root_ / "out").string();
  RunResult r = batch(base + " -map " + (root_ / "oxts.pcd").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Input " + drive.string() + ": KITTI raw drive, 3 frame(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Poses: OXTS packets " + (drive / "oxts" / "data").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3/3 frames"), std::string::npos) << r.output;
  // The same map as from a poses file of the same camera poses; another one moves it.
  r = batch(base + " -map " + (root_ / "given.pcd").string() + " -poses " + (root_ / "forward.txt").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Poses: poses file " + (root_ / "forward.txt").string() + " (-poses)"), std::string::npos)
      << r.output;
  EXPECT_NEAR(static_cast<double>(sizeOf(root_ / "oxts.pcd")), static_cast<double>(sizeOf(root_ / "given.pcd")),
              0.001 * static_cast<double>(sizeOf(root_ / "given.pcd")));
  const Eigen::Vector3d same = meanOf(root_ / "oxts.pcd") - meanOf(root_ / "given.pcd");
  EXPECT_LT(same.norm(), 1e-3) << same.transpose();
  r = batch(base + " -map " + (root_ / "still.pcd").string() + " -poses " + (root_ / "still.txt").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GT((meanOf(root_ / "oxts.pcd") - meanOf(root_ / "still.pcd")).norm(), 1.0);

  // A missing packet is named before any frame runs.
  fs::remove(drive / "oxts" / "data" / "0000000001.txt");
  r = batch("-input_dir " + drive.string() + " -output_dir " + (root_ / "out2").string() + " -map " +
            (root_ / "missing.pcd").string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("cannot read the OXTS packet '" + (drive / "oxts" / "data" / "0000000001.txt").string() + "'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(root_ / "out2" / "0000000000.pcd")) << "a frame was run";
}

TEST_F(BatchMap, RefusalsNameTheProblemBeforeAnyFrameIsRun) {
  const fs::path seq = sequenceWith(forwardPoses(1.0));
  const std::string base = "-input_dir " + seq.string() + " -output_dir " + (root_ / "out").string();
  const std::string map = " -map " + (root_ / "map.pcd").string();
  struct Case {
    std::string arguments;
    std::string message;
  };
  std::ofstream(root_ / "two.txt") << forwardPoses(1.0, 2);
  for (const Case& c : {Case{map + " -shard 0/2", "option -map: the map needs every frame, but -shard 0/2"},
                        Case{" -map " + (root_ / "map.xyz").string(), "option -map: "},
                        Case{map + " -map_picture " + (root_ / "top.jpg").string(), "must be a .png file"},
                        Case{map + " -map_voxel 0", "option -map_voxel: must be > 0"},
                        Case{" -poses " + (root_ / "two.txt").string(), "option -poses needs -map OUT.pcd"},
                        Case{map + " -poses " + (root_ / "two.txt").string(),
                             "has 2 poses but the sequence has 3 frames"}}) {
    const RunResult r = batch(base + c.arguments);
    EXPECT_NE(r.exitCode, 0) << c.arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.arguments << "\n" << r.output;
    EXPECT_FALSE(fs::exists(root_ / "out" / "000000.pcd")) << c.arguments << ": a frame was run";
  }
  // Several sequences: the map is of one drive.
  const fs::path root = root_ / "two_sequences";
  fs::create_directories(root / "sequences");
  fs::copy(seq, root / "sequences" / "00", fs::copy_options::recursive);
  fs::copy(seq, root / "sequences" / "01", fs::copy_options::recursive);
  const RunResult r = batch("-input_dir " + root.string() + " -output_dir " + (root_ / "out").string() + map);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2 KITTI odometry sequences (00, 01)"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lidar_sgm
