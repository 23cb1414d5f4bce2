// A KITTI raw drive's poses from its OXTS packets: packets written for a vehicle whose path is
// known by construction (east, then north with a quarter turn and a climb, then rolled and
// pitched) give the left camera's poses that path and the calibration's chain imply; a missing or
// malformed packet or calibration file is named.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/oxts_poses.hpp"
#include "lidar_sgm/sequence/poses.hpp"

namespace lidar_sgm {
namespace sequence {
namespace {
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kEarthRadius = 6378137.0;
constexpr double kLatitude0 = 49.0;  // [deg], about KITTI's Karlsruhe
constexpr double kLongitude0 = 8.4;
constexpr double kAltitude0 = 110.0;

/// The pose of the vehicle (IMU) in the world of the first packet (east, north, up; the first
/// heading east, level), and what its packet says.
struct Waypoint {
  Eigen::Vector3d position;  ///< [m] east, north, up from the first packet
  double roll, pitch, yaw;   ///< [rad]
};

/// A packet line for `w`: latitude and longitude found by inverting the Mercator projection at
/// the first packet's scale, so that the projection gives `w.position` back.
std::string packetOf(const Waypoint& w) {
  const double s = std::cos(kLatitude0 * kPi / 180.0);
  const double x0 = s * kEarthRadius * kLongitude0 * kPi / 180.0;
  const double y0 = s * kEarthRadius * std::log(std::tan((90.0 + kLatitude0) * kPi / 360.0));
  const double longitude = (x0 + w.position.x()) / (s * kEarthRadius) * 180.0 / kPi;
  const double latitude = std::atan(std::exp((y0 + w.position.y()) / (s * kEarthRadius))) * 360.0 / kPi - 90.0;
  char text[512];
  std::snprintf(text, sizeof(text), "%.17g %.17g %.17g %.17g %.17g %.17g", latitude, longitude,
                kAltitude0 + w.position.z(), w.roll, w.pitch, w.yaw);
  // The 24 other values (velocities, accelerations, accuracies, modes), as KITTI writes them.
  return std::string(text) + " 0.1 0.2 12.5 0.3 0.01 0.1 0.2 9.8 0.1 0.2 9.8 0.001 0.002 0.003 0.001 0.002 0.003 "
                             "0.5 0.05 4 10 4 4 6\n";
}

Eigen::Isometry3d poseOf(const Waypoint& w) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = w.position;
  pose.linear() = (Eigen::AngleAxisd(w.yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(w.pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(w.roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

Eigen::Isometry3d rigid(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

std::string rowMajor(const Eigen::Matrix3d& R) {
  std::string text;
  char number[40];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      std::snprintf(number, sizeof(number), " %.17g", R(r, c));
      text += number;
    }
  }
  return text;
}

/// The same transform, compared within `tolerance` relative to its translation's size.
void expectNear(const Eigen::Isometry3d& actual, const Eigen::Isometry3d& expected, double tolerance,
                const std::string& what) {
  const double scale = std::max(1.0, expected.translation().norm());
  EXPECT_LT((actual.translation() - expected.translation()).norm(), tolerance * scale)
      << what << ": " << actual.translation().transpose() << " vs " << expected.translation().transpose();
  EXPECT_LT((actual.linear() - expected.linear()).cwiseAbs().maxCoeff(), tolerance) << what;
}

class OxtsPoses : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("lidar_sgm_oxts_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(getpid()));
    fs::remove_all(root_);
    date_ = root_ / "2011_09_26";
    drive_ = date_ / "2011_09_26_drive_0001_sync";
    fs::create_directories(drive_ / "oxts" / "data");
    fs::create_directories(drive_ / "velodyne_points" / "data");
    // A rig like KITTI's: camera 2 0.06 m right of camera 0 (P_rect_02[0,3] = fx * 0.06), a
    // slightly turned R_rect_00, the LiDAR's axes swapped into the camera's, the IMU behind and
    // below the LiDAR and turned a little about z.
    write(date_ / "calib_cam_to_cam.txt",
          "calib_time: 09-Jan-2012 13:57:47\n"
          "P_rect_02: 700 0 600 42 0 700 180 0 0 0 1 0\n"
          "P_rect_03: 700 0 600 -336 0 700 180 0 0 0 1 0\n"
          "R_rect_00:" + rowMajor(rectification()) + "\n"
          "S_rect_02: 1.242000e+03 3.750000e+02\n");
    write(date_ / "calib_velo_to_cam.txt",
          "calib_time: 15-Mar-2012 11:37:16\nR:" + rowMajor(cameraFromLidar().linear()) + "\nT: 0 -0.08 -0.27\n");
    write(date_ / "calib_imu_to_velo.txt",
          "calib_time: 25-May-2012 16:47:16\nR:" + rowMajor(lidarFromImu().linear()) + "\nT: -0.81 0.32 -0.8\n");
  }
  void TearDown() override { fs::remove_all(root_); }

  static void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

  static Eigen::Matrix3d rectification() { return Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
  static Eigen::Isometry3d cameraFromLidar() {
    Eigen::Matrix3d R;
    R << 0, -1, 0, 0, 0, -1, 1, 0, 0;
    return rigid(R, Eigen::Vector3d(0, -0.08, -0.27));
  }
  static Eigen::Isometry3d lidarFromImu() {
    return rigid(Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitZ()).toRotationMatrix(), Eigen::Vector3d(-0.81, 0.32, -0.8));
  }
  /// The rectified left (color) camera from the IMU, composed by hand from the files above:
  /// camera 2's offset, R_rect_00, calib_velo_to_cam, calib_imu_to_velo.
  static Eigen::Isometry3d cameraFromImu() {
    return rigid(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.06, 0, 0)) *
           rigid(rectification(), Eigen::Vector3d::Zero()) * cameraFromLidar() * lidarFromImu();
  }

  /// The drive's frames with one packet per waypoint.
  std::vector<Frame> driveThrough(const std::vector<Waypoint>& path) {
    for (std::size_t i = 0; i < path.size(); ++i) {
      char stem[32];
      std::snprintf(stem, sizeof(stem), "%010zu", i);
      std::ofstream(drive_ / "velodyne_points" / "data" / (std::string(stem) + ".bin")) << "";
      write(drive_ / "oxts" / "data" / (std::string(stem) + ".txt"), packetOf(path[i]));
    }
    return framesFromDirectory(drive_.string());
  }

  fs::path root_;
  fs::path date_;
  fs::path drive_;
};

const std::vector<Waypoint> kPath = {
    {{0, 0, 0}, 0, 0, 0},                          // heading east, level
    {{10, 0, 0}, 0, 0, 0},                         // 10 m east
    {{10, 5, 1.5}, 0, 0, kPi / 2},                 // then 5 m north, turned to face north, 1.5 m up
    {{4, 25, 3}, 0.03, -0.05, kPi / 2 + 0.3}};     // rolled, pitched, turned on

TEST_F(OxtsPoses, PacketsOfAKnownDriveGiveTheLeftCamerasPosesOfThatDrive) {
  const std::vector<Frame> frames = driveThrough(kPath);
  ASSERT_EQ(frames.size(), kPath.size());
  const SequencePoses poses = posesOfSequence(frames, "");
  ASSERT_EQ(poses.poses.size(), kPath.size());
  EXPECT_NE(poses.source.find("OXTS packets " + (drive_ / "oxts" / "data").string()), std::string::npos)
      << poses.source;

  // The first packet is level and faces east, so the IMU's world is that of frame 0: the
  // vehicle's pose i is the waypoint's, and the camera's is it seen through the rig.
  const Eigen::Isometry3d T = cameraFromImu();
  for (std::size_t i = 0; i < kPath.size(); ++i) {
    expectNear(poses.poses[i], T * poseOf(kPath[i]) * T.inverse(), 1e-6, "frame " + std::to_string(i));
  }
  EXPECT_TRUE(poses.poses[0].isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  // Driving straight ahead moves the camera along its own optical axis (z), by the distance.
  const Eigen::Vector3d ahead = poses.poses[1].translation();
  EXPECT_NEAR(ahead.norm(), 10.0, 1e-6);
  EXPECT_GT(ahead.z(), 9.9) << ahead.transpose();
  // A quarter turn left (counter-clockwise seen from above) turns the camera about its -y (up).
  const Eigen::AngleAxisd turn(poses.poses[2].linear());
  EXPECT_NEAR(turn.angle(), kPi / 2, 1e-6);
  EXPECT_LT((turn.axis() - T.linear() * Eigen::Vector3d::UnitZ()).norm(), 1e-6) << turn.axis().transpose();
}

TEST_F(OxtsPoses, PosesAreRelativeToTheFirstPacketWhereverItFaces) {
  // The same drive started 40 m further north, heading 30 degrees left of east and pitched:
  // relative to its first pose, the same motion.
  const Eigen::Isometry3d start = poseOf({{0, 40, 2}, 0, 0.02, 0.5});
  std::vector<Waypoint> moved;
  for (const Waypoint& w : kPath) {
    const Eigen::Isometry3d world = start * poseOf(w);
    const Eigen::Vector3d yawPitchRoll = world.linear().eulerAngles(2, 1, 0);
    moved.push_back({world.translation(), yawPitchRoll[2], yawPitchRoll[1], yawPitchRoll[0]});
  }
  // The first packet's own latitude sets the Mercator scale: place the drive's first packet there.
  const std::vector<Frame> frames = driveThrough(moved);
  const std::vector<Eigen::Isometry3d> poses = posesOfSequence(frames, "").poses;
  const Eigen::Isometry3d T = cameraFromImu();
  // The scale is the first packet's latitude's (40 m north of kLatitude0): distances differ from
  // the waypoints' by cos(lat) / cos(lat0) - 1, about 1e-5 relative.
  for (std::size_t i = 0; i < kPath.size(); ++i) {
    expectNear(poses[i], T * poseOf(kPath[i]) * T.inverse(), 2e-5, "frame " + std::to_string(i));
  }
}

TEST_F(OxtsPoses, TheDevkitsConversionOfPacketsInTheWorld) {
  // Straight from the packets (no files): the first is the identity, then the Mercator metres.
  OxtsPacket first;
  first.latitude = kLatitude0;
  first.longitude = kLongitude0;
  first.altitude = kAltitude0;
  OxtsPacket second = first;
  second.longitude += 1e-3;  // east: s * r * 1e-3 deg
  second.altitude += 2.0;
  second.yaw = -0.25;
  const std::vector<Eigen::Isometry3d> poses = imuPosesFromOxts({first, second});
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_TRUE(poses[0].isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  const double east = std::cos(kLatitude0 * kPi / 180.0) * kEarthRadius * 1e-3 * kPi / 180.0;
  EXPECT_LT((poses[1].translation() - Eigen::Vector3d(east, 0, 2)).norm(), 1e-6 * east);
  EXPECT_LT((poses[1].linear() - Eigen::AngleAxisd(-0.25, Eigen::Vector3d::UnitZ()).toRotationMatrix()).norm(), 1e-12);
  EXPECT_TRUE(imuPosesFromOxts({}).empty());
}

TEST_F(OxtsPoses, AMissingOrMalformedPacketOrCalibrationIsNamed) {
  const std::vector<Frame> frames = driveThrough(kPath);
  const std::string packet = (drive_ / "oxts" / "data" / "0000000002.txt").string();
  const auto errorOf = [&] {
    try {
      posesOfSequence(frames, "");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  struct Case {
    std::string text;  ///< frame 2's packet; "" removes it
    std::string message;
  };
  const std::string good = packetOf(kPath[2]);
  const std::string values = good.substr(0, good.size() - 1);
  for (const Case& c : {Case{"", "cannot read the OXTS packet '" + packet + "'"},
                        Case{"49.0 8.4 110 0 0 0\n", "'" + packet + "': expected 30 numbers (lat lon alt roll pitch yaw"},
                        Case{"\n", "got 0"},
                        Case{values + " 7\n", "got 31"},
                        Case{"abc" + values.substr(values.find(' ')) + "\n", "line 1: 'abc' is not a number"},
                        Case{values + "\n" + values + "\n", "line 2: a packet is one line"},
                        Case{"95" + values.substr(values.find(' ')) + "\n", "latitude 95 is not within (-90, 90)"},
                        Case{"49 8.4 110 0 0 90" + values.substr(values.find(" 0.1 0.2 12.5")) + "\n",
                             "yaw 90 is not within"}}) {
    fs::remove(packet);
    if (!c.text.empty()) write(packet, c.text);
    const std::string error = errorOf();
    EXPECT_NE(error.find(c.message), std::string::npos) << c.text << ": " << error;
    EXPECT_NE(error.find("unless -poses FILE is given"), std::string::npos) << error;
  }
  write(packet, good);
  EXPECT_EQ(errorOf(), "");

  fs::remove(date_ / "calib_imu_to_velo.txt");
  EXPECT_NE(errorOf().find((date_ / "calib_imu_to_velo.txt").string()), std::string::npos) << errorOf();
  write(date_ / "calib_imu_to_velo.txt", "R: 1 0 0 0 1 0 0 0 1\n");
  EXPECT_NE(errorOf().find("missing key 'T'"), std::string::npos) << errorOf();

  // -poses wins over the packets, which are then not read.
  fs::remove_all(drive_ / "oxts");
  const fs::path given = root_ / "poses.txt";
  std::ofstream out(given);
  for (std::size_t i = 0; i < kPath.size(); ++i) out << "1 0 0 0 0 1 0 0 0 0 1 " << i << "\n";
  out.close();
  EXPECT_EQ(posesOfSequence(frames, given.string()).source, "poses file " + given.string() + " (-poses)");
}

}  // namespace
}  // namespace sequence
}  // namespace lidar_sgm
