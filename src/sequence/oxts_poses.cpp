#include "lidar_sgm/sequence/oxts_poses.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "number_line.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

namespace fs = std::filesystem;

namespace lidar_sgm {
namespace sequence {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// The earth radius of the KITTI raw devkit's Mercator projection (WGS84's equatorial) [m].
constexpr double kEarthRadius = 6378137.0;

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

void requireWithin(double value, double limit, bool inclusive, const std::string& where, const char* name,
                   const char* unit) {
  if (inclusive ? std::abs(value) <= limit : std::abs(value) < limit) return;
  throw std::invalid_argument(where + ": " + name + " " + numberText(value) + " is not within " +
                              (inclusive ? "[-" : "(-") + numberText(limit) + ", " + numberText(limit) +
                              (inclusive ? "] " : ") ") + unit);
}

}  // namespace

OxtsPacket readOxtsPacket(const std::string& path) {
  const std::string where = "OXTS packet '" + path + "'";
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read the " + where);
  std::vector<double> values;
  int lines = 0;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (++lines > 1) throw std::invalid_argument(where + " line " + std::to_string(number) + ": a packet is one line");
    values = numbersOfLine(line, where + " line " + std::to_string(number));
  }
  if (values.size() != kOxtsPacketValues) {
    throw std::invalid_argument(where + ": expected " + std::to_string(kOxtsPacketValues) +
                                " numbers (lat lon alt roll pitch yaw vn ve ...), got " +
                                std::to_string(values.size()));
  }
  OxtsPacket packet;
  packet.latitude = values[0];
  packet.longitude = values[1];
  packet.altitude = values[2];
  packet.roll = values[3];
  packet.pitch = values[4];
  packet.yaw = values[5];
  requireWithin(packet.latitude, 90.0, false, where, "latitude", "degrees");
  requireWithin(packet.longitude, 180.0, true, where, "longitude", "degrees");
  // The angles are radians: a packet in degrees would pass as a wild rotation.
  requireWithin(packet.roll, 2.0 * kPi, true, where, "roll", "radians");
  requireWithin(packet.pitch, 2.0 * kPi, true, where, "pitch", "radians");
  requireWithin(packet.yaw, 2.0 * kPi, true, where, "yaw", "radians");
  return packet;
}

std::vector<Eigen::Isometry3d> imuPosesFromOxts(const std::vector<OxtsPacket>& packets) {
  std::vector<Eigen::Isometry3d> poses;
  if (packets.empty()) return poses;
  // KITTI raw devkit, convertOxtsToPose (after latToScale and latlonToMercator): a Mercator
  // projection whose scale, cos(latitude), is the first packet's for the whole drive.
  const double scale = std::cos(packets.front().latitude * kPi / 180.0);
  Eigen::Isometry3d firstInverse = Eigen::Isometry3d::Identity();
  for (const OxtsPacket& p : packets) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() << scale * kEarthRadius * p.longitude * kPi / 180.0,
        scale * kEarthRadius * std::log(std::tan((90.0 + p.latitude) * kPi / 360.0)), p.altitude;
    pose.linear() = (Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(p.pitch, Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(p.roll, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    // Relative to the first pose, as the devkit's Tr_0_inv * pose.
    if (poses.empty()) firstInverse = pose.inverse();
    poses.push_back(firstInverse * pose);
  }
  return poses;
}

std::vector<Eigen::Isometry3d> cameraPosesFromImuPoses(const std::vector<Eigen::Isometry3d>& imuPoses,
                                                       const Eigen::Isometry3d& cameraFromImu) {
  const Eigen::Isometry3d imuFromCamera = cameraFromImu.inverse();
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(imuPoses.size());
  for (const Eigen::Isometry3d& imuPose : imuPoses) poses.push_back(cameraFromImu * imuPose * imuFromCamera);
  return poses;
}

std::string oxtsFolderOf(const std::vector<Frame>& frames) {
  return frames.empty() ? std::string() : fs::path(frames.front().oxts).parent_path().string();
}

std::vector<Eigen::Isometry3d> oxtsPosesOfDrive(const std::vector<Frame>& frames) {
  if (frames.empty()) return {};
  for (const Frame& frame : frames) {
    if (frame.oxts.empty()) {
      throw std::invalid_argument("frame " + frame.name + " has no OXTS packet: only a KITTI raw drive has them");
    }
    if (frame.calib != frames.front().calib) {
      throw std::invalid_argument("frames " + frames.front().name + " and " + frame.name +
                                  " have different calibrations: the OXTS poses are of one drive");
    }
  }
  // Every packet before any frame runs: a bad one is named now, not after the densification.
  std::vector<OxtsPacket> packets;
  packets.reserve(frames.size());
  for (const Frame& frame : frames) packets.push_back(readOxtsPacket(frame.oxts));

  // The calibration's rectified left camera from the IMU: T_cam_lidar (calib_velo_to_cam.txt,
  // R_rect_00, camera 2's offset, as the frames are densified) after calib_imu_to_velo.txt.
  const fs::path calib(frames.front().calib);
  std::error_code ec;
  const fs::path dateFolder = fs::is_directory(calib, ec) ? calib : calib.parent_path();
  Eigen::Isometry3d cameraFromImu;
  try {
    const Eigen::Isometry3d lidarFromImu =
        io::readKittiRawRigidTransform((dateFolder / "calib_imu_to_velo.txt").string());
    cameraFromImu = readFrameCalibration(frames.front()).T_cam_lidar * lidarFromImu;
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(std::string("the OXTS poses need the drive's calibration: ") + e.what());
  }
  return cameraPosesFromImuPoses(imuPosesFromOxts(packets), cameraFromImu);
}

}  // namespace sequence
}  // namespace lidar_sgm
