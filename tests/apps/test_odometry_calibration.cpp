// lidar_sgm_batch's pieces: the KITTI odometry calib.txt, read as the object format it stands for.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "apps/frame_list_fixture.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace apps {
namespace {

// A KITTI odometry calib.txt (values of sequence 00) and the object-format text it stands for.
const char* const kOdometryCalib =
    "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n"
    "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n"
    "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 3.779761000000e-03\n"
    "P3: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.372877000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 2.369057000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 4.915215000000e-03\n"
    "Tr: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
    "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 9.999738645903e-01 "
    "4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01\n";

TEST_F(FrameList, OdometryCalibrationIsTheObjectFormatWithIdentityRectificationAndTrAsVeloToCam) {
  write(root_ / "calib.txt", kOdometryCalib);
  const geometry::StereoCalibration odometry =
      io::readKittiOdometryCalibration((root_ / "calib.txt").string(), 1241, 376);
  std::string objectText = kOdometryCalib;
  objectText.replace(objectText.find("Tr:"), 3, "Tr_velo_to_cam:");
  objectText += "R0_rect: 1 0 0 0 1 0 0 0 1\n";
  const geometry::StereoCalibration object = io::readKittiCalibrationFromString(objectText, "object", 1241, 376);
  EXPECT_EQ(odometry.width, 1241);
  EXPECT_EQ(odometry.height, 376);
  EXPECT_EQ(odometry.baseline, object.baseline);
  EXPECT_TRUE(odometry.K == object.K);
  EXPECT_TRUE(odometry.T_cam_lidar.matrix() == object.T_cam_lidar.matrix());
  // The KITTI odometry stereo baseline is about 0.54 m.
  EXPECT_NEAR(odometry.baseline, 0.54, 0.01);

  sequence::Frame frame;
  frame.calib = (root_ / "calib.txt").string();
  frame.calibFormat = sequence::CalibrationFormat::KittiOdometry;
  EXPECT_EQ(sequence::readFrameCalibration(frame, 1241, 376).baseline, odometry.baseline);
  frame.calibFormat = sequence::CalibrationFormat::Auto;  // read as the object format, it lacks R0_rect
  EXPECT_THROW(sequence::readFrameCalibration(frame, 1241, 376), std::runtime_error);
}

TEST_F(FrameList, OdometryCalibrationWithoutTrIsRefusedNamingTheFile) {
  write(root_ / "calib.txt", "P2: 1 0 0 0 0 1 0 0 0 0 1 0\n");
  try {
    io::readKittiOdometryCalibration((root_ / "calib.txt").string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("calib.txt' has no 'Tr:' line"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::readKittiOdometryCalibration((root_ / "missing.txt").string()), std::runtime_error);
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
