// lidar_sgm_batch -map's pieces: the poses file, and where a frame's cloud lands in the world.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "apps/map_pieces_fixture.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/frame_to_world.hpp"
#include "lidar_sgm/sequence/poses.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
namespace fs = std::filesystem;

const char* const kIdentity = "1 0 0 0 0 1 0 0 0 0 1 0\n";

// --- poses ------------------------------------------------------------------------------------

TEST_F(MapPieces, PosesFileGivesOneRowMajorPosePerLine) {
  // Frame 1: turned 90 degrees about y (x' = z, z' = -x), at (1, 2, 3); exponents as KITTI prints.
  const std::string path = write(root_ / "poses.txt", std::string(kIdentity) +
                                                          "0.0 0 1.000000e+00 1 0 1 0 2 -1 0 0 3.0e0\n");
  const std::vector<Eigen::Isometry3d> poses = sequence::readPoses(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_TRUE(poses[0].isApprox(Eigen::Isometry3d::Identity()));
  const Eigen::Vector3d moved = poses[1] * Eigen::Vector3d(1, 0, 0);
  EXPECT_TRUE(moved.isApprox(Eigen::Vector3d(1, 2, 2))) << moved.transpose();
  EXPECT_EQ(poses[1].matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST_F(MapPieces, EachBadPosesLineIsNamedByFileAndLine) {
  struct Case {
    const char* secondLine;
    const char* problem;
  };
  for (const Case& c : {Case{"1 0 0 0 0 1 0 0 0 0 1", "expected 12 numbers (a row-major 3x4 pose), got 11"},
                        Case{"1 0 0 0 0 1 0 0 0 0 1 0 5", "got 13"},
                        Case{"", "got 0"},
                        Case{"1 0 0 0 0 1 0 0 0 0 1 x", "'x' is not a number"},
                        Case{"1 0 0 0 0 1 0 0 0 0 1 0.5m", "'0.5m' is not a number"},
                        Case{"1 0 0 nan 0 1 0 0 0 0 1 0", "'nan' is not a finite number"},
                        Case{"1 0 0 0 0 1 0 0 0 0 1 1e999", "'1e999' is not a finite number"},
                        Case{"2 0 0 0 0 1 0 0 0 0 1 0", "not a rigid transform"},
                        Case{"1 0 0 0 0 1 0 0 0 0 -1 0", "not a rigid transform"},      // a reflection
                        Case{"1 0.01 0 0 0 1 0 0 0 0 1 0", "not a rigid transform"}}) {  // sheared beyond 1e-3
    const std::string path = write(root_ / "poses.txt", std::string(kIdentity) + c.secondLine + "\n" + kIdentity);
    const std::string error = errorOf([&] { sequence::readPoses(path); });
    EXPECT_NE(error.find("poses file '" + path + "' line 2: "), std::string::npos) << c.secondLine << ": " << error;
    EXPECT_NE(error.find(c.problem), std::string::npos) << c.secondLine << ": " << error;
  }
  // Within the tolerance: KITTI's printed digits.
  const std::string path = write(root_ / "close.txt", "1 0.0004 0 0 -0.0004 1 0 0 0 0 1 0\n");
  EXPECT_EQ(sequence::readPoses(path).size(), 1u);
  EXPECT_NE(errorOf([&] { sequence::readPoses((root_ / "missing.txt").string()); }).find("cannot read the poses file"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { sequence::readPoses(write(root_ / "empty.txt", "")); }).find("has no pose"), std::string::npos);
}

/// Frames of a KITTI odometry sequence folder (only paths matter here).
std::vector<sequence::Frame> odometryFrames(const fs::path& sequenceDir, int count) {
  std::vector<sequence::Frame> frames(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    sequence::Frame& f = frames[static_cast<std::size_t>(i)];
    f.name = "00000" + std::to_string(i);
    f.scan = (sequenceDir / "velodyne" / (f.name + ".bin")).string();
    f.calib = (sequenceDir / "calib.txt").string();
    f.calibFormat = sequence::CalibrationFormat::KittiOdometry;
  }
  return frames;
}

TEST_F(MapPieces, PosesAreFoundInTheSequenceFolderFirstThenInTheDatasetsPosesFolder) {
  const fs::path sequenceDir = root_ / "dataset" / "sequences" / "07";
  const std::vector<sequence::Frame> frames = odometryFrames(sequenceDir, 2);
  EXPECT_EQ(sequence::findPosesFile(frames), "");
  const std::string dataset = write(root_ / "dataset" / "poses" / "07.txt", std::string(kIdentity) + kIdentity);
  EXPECT_EQ(fs::path(sequence::findPosesFile(frames)), fs::path(dataset));
  const std::string own = write(sequenceDir / "poses.txt", std::string(kIdentity) + kIdentity);
  EXPECT_EQ(fs::path(sequence::findPosesFile(frames)), fs::path(own));
  EXPECT_EQ(sequence::posesOfSequence(frames, "").poses.size(), 2u);

  std::vector<sequence::Frame> object = frames;
  for (sequence::Frame& f : object) f.calibFormat = sequence::CalibrationFormat::Auto;
  EXPECT_EQ(sequence::findPosesFile(object), "") << "only an odometry sequence has poses of its own";
  EXPECT_NE(errorOf([&] { sequence::posesOfSequence(object, ""); }).find("give -poses FILE"), std::string::npos);
  EXPECT_EQ(sequence::posesOfSequence(object, own).poses.size(), 2u);
}

TEST_F(MapPieces, PoseCountMustBeTheFrameCountAndOneSequenceOnly) {
  const fs::path sequenceDir = root_ / "sequences" / "00";
  const std::string poses = write(sequenceDir / "poses.txt", std::string(kIdentity) + kIdentity + kIdentity);
  const std::string error = errorOf([&] { sequence::posesOfSequence(odometryFrames(sequenceDir, 2), ""); });
  EXPECT_NE(error.find("'" + poses + "' has 3 poses but the sequence has 2 frames"), std::string::npos) << error;

  std::vector<sequence::Frame> two = odometryFrames(sequenceDir, 1);
  const std::vector<sequence::Frame> other = odometryFrames(root_ / "sequences" / "01", 1);
  two.insert(two.end(), other.begin(), other.end());
  for (const std::string& given : {std::string(), poses}) {
    const std::string several = errorOf([&] { sequence::posesOfSequence(two, given); });
    EXPECT_NE(several.find("2 KITTI odometry sequences (00, 01)"), std::string::npos) << several;
  }
}

// --- the transform ----------------------------------------------------------------------------

/// A KITTI odometry calib.txt whose camera 2 is 0.06 m right of camera 0 (P2[0,3] = fx * 0.06,
/// as KITTI's color camera), Tr the usual axes swap with an offset.
std::string odometryCalibration() {
  return "P0: 700 0 600 0 0 700 180 0 0 0 1 0\n"
         "P1: 700 0 600 -378 0 700 180 0 0 0 1 0\n"
         "P2: 700 0 600 42 0 700 180 0 0 0 1 0\n"
         "P3: 700 0 600 -336 0 700 180 0 0 0 1 0\n"
         "Tr: 0 -1 0 0 0 0 -1 -0.08 1 0 0 -0.27\n";
}

TEST_F(MapPieces, AFramesCloudLandsWhereItsPoseAndCalibrationPutIt) {
  const std::string calibPath = write(root_ / "00" / "calib.txt", odometryCalibration());
  sequence::Frame frame;
  frame.calib = calibPath;
  frame.calibFormat = sequence::CalibrationFormat::KittiOdometry;
  const geometry::StereoCalibration calibration = sequence::readFrameCalibration(frame);
  // The pose: turned 90 degrees about y (x' = z, z' = -x), at (1, 0, 5).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  pose.translation() = Eigen::Vector3d(1, 0, 5);

  // LiDAR (10, 2, 1) -> camera 0 by Tr: (-2, -1 - 0.08, 10 - 0.27) -> world: (9.73 + 1, -1.08, 2 + 5).
  const Eigen::Vector3d lidarPoint(10, 2, 1);
  const Eigen::Vector3d expected(10.73, -1.08, 7);
  const Eigen::Isometry3d lidarToWorld =
      sequence::cloudToWorld(pose, sequence::poseCameraFromLidar(frame, calibration), calibration, geometry::OutputFrame::Lidar);
  EXPECT_LT((lidarToWorld * lidarPoint - expected).norm(), 1e-12) << (lidarToWorld * lidarPoint).transpose();

  // The same point written in the camera frame is in camera 2 (its x is camera 0's + 0.06 m):
  // it must land at the same place; had the pose been read as camera 2's, it would be 0.06 m off.
  const Eigen::Vector3d cameraPoint = calibration.T_cam_lidar * lidarPoint;
  EXPECT_LT((cameraPoint - Eigen::Vector3d(-2 + 0.06, -1.08, 9.73)).norm(), 1e-12) << cameraPoint.transpose();
  const Eigen::Isometry3d cameraToWorld =
      sequence::cloudToWorld(pose, sequence::poseCameraFromLidar(frame, calibration), calibration, geometry::OutputFrame::Camera);
  EXPECT_LT((cameraToWorld * cameraPoint - expected).norm(), 1e-12) << (cameraToWorld * cameraPoint).transpose();

  // Another layout has no camera 0: its poses are of the calibration's left camera.
  sequence::Frame object = frame;
  object.calibFormat = sequence::CalibrationFormat::Auto;
  EXPECT_TRUE(sequence::poseCameraFromLidar(object, calibration).isApprox(calibration.T_cam_lidar));
  // A file that is not what it should be is the io readers' std::runtime_error.
  try {
    io::readKittiOdometryTr(write(root_ / "noTr.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n"));
    ADD_FAILURE() << "a calib.txt without Tr was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no 'Tr:' line"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
