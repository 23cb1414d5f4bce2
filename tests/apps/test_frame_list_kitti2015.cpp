// lidar_sgm_batch's frame discovery in KITTI stereo 2015's training layout with the raw scans
// beside it: both forms of its calibration (one shared KITTI raw pair, or KITTI 2015's own per
// frame), the folders and _11 images that are not frames, and the messages for a broken layout.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/frame_list_fixture.hpp"
#include "common/test_paths.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The text of KITTI raw's calib_cam_to_cam.txt / calib_velo_to_cam.txt: the real 2011_09_26 one
/// of ../shared/data/kitti2015_lidar when it is there, else the keys the reader needs, with the
/// same numbers (the test must not depend on the data set to run).
std::string calibText(const char* file) {
  const fs::path real = fs::path(test::kSharedDataDir) / "kitti2015_lidar" / "calib" / file;
  if (fs::is_regular_file(real)) return readText(real);
  if (std::string(file) == "calib_velo_to_cam.txt") {
    return "R: 7.533745e-03 -9.999714e-01 -6.166020e-04 1.480249e-02 7.280733e-04 -9.998902e-01 9.998621e-01 "
           "7.523790e-03 1.480755e-02\nT: -4.069766e-03 -7.631618e-02 -2.717806e-01\n";
  }
  return "S_rect_02: 1.242000e+03 3.750000e+02\n"
         "R_rect_00: 1 0 0 0 1 0 0 0 1\n"
         "P_rect_02: 7.215377e+02 0 6.095593e+02 4.485728e+01 0 7.215377e+02 1.728540e+02 2.163791e-01 0 0 1 "
         "2.745884e-03\n"
         "P_rect_03: 7.215377e+02 0 6.095593e+02 -3.395242e+02 0 7.215377e+02 1.728540e+02 2.199936e+00 0 0 1 "
         "2.729905e-03\n";
}

class Kitti2015Layout : public FrameList {
 protected:
  /// Two frames with scans (000007_10, 000012_10) in KITTI 2015's training folders: their _11
  /// images, a frame without a scan (000099_10), and the ground-truth folders beside them.
  void writeFrames() {
    for (const char* id : {"000007", "000012", "000099"}) {
      for (const char* instant : {"_10", "_11"}) {
        for (const char* folder : {"image_2", "image_3"}) touch(root_ / folder / (std::string(id) + instant + ".png"));
      }
      touch(root_ / "disp_occ_0" / (std::string(id) + "_10.png"));
      touch(root_ / "obj_map" / (std::string(id) + "_10.png"));
    }
    touch(root_ / "velodyne" / "000007_10.bin");
    touch(root_ / "velodyne" / "000012_10.bin");
  }
  void writeSharedCalibration() {
    for (const char* file : {"calib_cam_to_cam.txt", "calib_velo_to_cam.txt"}) {
      write(root_ / "calib" / file, calibText(file));
    }
  }
  /// KITTI 2015's own calibration files of one frame, named `name`.txt.
  void writeFrameCalibration(const std::string& name) {
    write(root_ / "calib_cam_to_cam" / (name + ".txt"), calibText("calib_cam_to_cam.txt"));
    write(root_ / "calib_velo_to_cam" / (name + ".txt"), calibText("calib_velo_to_cam.txt"));
  }
  std::string errorOf() {
    try {
      sequence::framesFromDirectory(root_.string());
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  }
};

void expectSameCalibration(const geometry::StereoCalibration& a, const geometry::StereoCalibration& b) {
  EXPECT_EQ(a.K, b.K);
  EXPECT_EQ(a.baseline, b.baseline);
  EXPECT_EQ(a.T_cam_lidar.matrix(), b.T_cam_lidar.matrix());
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
}

TEST_F(Kitti2015Layout, OnlyScannedFramesWithTheSharedCalibrationAsLidarSgmDensifyReadsIt) {
  writeFrames();
  writeSharedCalibration();
  EXPECT_EQ(sequence::directoryLayout(root_.string()), sequence::Layout::KittiStereo2015)
      << "not the object layout, although it has velodyne/ and calib/";
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::KittiStereo2015), "KITTI stereo 2015 training");
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(root_.string());
  ASSERT_EQ(frames.size(), 2u) << "the _11 images and 000099_10 (no scan) are no frames";
  EXPECT_EQ(frames[0].name, "000007_10");
  EXPECT_EQ(frames[1].name, "000012_10");
  EXPECT_EQ(frames[1].scan, (root_ / "velodyne" / "000012_10.bin").string());
  EXPECT_EQ(frames[1].left, (root_ / "image_2" / "000012_10.png").string());
  EXPECT_EQ(frames[1].right, (root_ / "image_3" / "000012_10.png").string());
  const std::string shared = (root_ / "calib" / "calib_cam_to_cam.txt").string();
  for (const sequence::Frame& frame : frames) {
    EXPECT_EQ(frame.calib, shared) << "what lidar_sgm_densify -calib is given";
    EXPECT_EQ(frame.calibFormat, sequence::CalibrationFormat::Auto);
    EXPECT_TRUE(frame.veloToCam.empty());
    EXPECT_TRUE(frame.oxts.empty());
    expectSameCalibration(sequence::readFrameCalibration(frame), io::readCalibration(shared));
  }
  EXPECT_EQ(sequence::readFrameCalibration(frames[0]).width, 1242);
}

TEST_F(Kitti2015Layout, PerFrameCalibrationByTheIdOrTheFramesNameWinsOverTheSharedOne) {
  writeFrames();
  writeSharedCalibration();
  writeFrameCalibration("000007");     // KITTI 2015's name: the id without _10
  writeFrameCalibration("000012_10");  // the frame's own name
  EXPECT_EQ(sequence::directoryLayout(root_.string()), sequence::Layout::KittiStereo2015);
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(root_.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].calib, (root_ / "calib_cam_to_cam" / "000007.txt").string());
  EXPECT_EQ(frames[0].veloToCam, (root_ / "calib_velo_to_cam" / "000007.txt").string());
  EXPECT_EQ(frames[1].calib, (root_ / "calib_cam_to_cam" / "000012_10.txt").string());
  EXPECT_EQ(frames[1].veloToCam, (root_ / "calib_velo_to_cam" / "000012_10.txt").string());
  const geometry::StereoCalibration shared = io::readCalibration((root_ / "calib" / "calib_cam_to_cam.txt").string());
  for (const sequence::Frame& frame : frames) {
    EXPECT_EQ(frame.calibFormat, sequence::CalibrationFormat::KittiRawPair);
    expectSameCalibration(sequence::readFrameCalibration(frame), shared);  // the same numbers in both files
  }
}

TEST_F(Kitti2015Layout, PerFrameCalibrationAloneAndAFrameWithoutItsFileFailsNamingIt) {
  writeFrames();
  writeFrameCalibration("000007");
  touch(root_ / "velodyne" / "000099_10.bin");  // no calib_cam_to_cam/000099.txt
  EXPECT_EQ(sequence::directoryLayout(root_.string()), sequence::Layout::KittiStereo2015);
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(root_.string());
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_NO_THROW(sequence::readFrameCalibration(frames[0]));
  EXPECT_EQ(frames[2].calib, (root_ / "calib_cam_to_cam" / "000099.txt").string());
  try {
    sequence::readFrameCalibration(frames[2]);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("calib_cam_to_cam/000099.txt"), std::string::npos) << e.what();
  }
}

TEST_F(Kitti2015Layout, ScansWithoutCalibrationAreRefusedNamingTheFilesLookedFor) {
  writeFrames();
  const std::string none = errorOf();
  EXPECT_NE(none.find("no calibration"), std::string::npos) << none;
  EXPECT_NE(none.find("calib/calib_cam_to_cam.txt with calib/calib_velo_to_cam.txt"), std::string::npos) << none;
  EXPECT_NE(none.find("calib_cam_to_cam/NNNNNN.txt with calib_velo_to_cam/NNNNNN.txt"), std::string::npos) << none;

  write(root_ / "calib" / "calib_cam_to_cam.txt", calibText("calib_cam_to_cam.txt"));
  const std::string halfShared = errorOf();
  EXPECT_NE(halfShared.find("has calib/calib_cam_to_cam.txt but no calib/calib_velo_to_cam.txt"), std::string::npos)
      << halfShared;

  fs::create_directories(root_ / "calib_velo_to_cam");
  const std::string halfPerFrame = errorOf();
  EXPECT_NE(halfPerFrame.find("has calib_velo_to_cam/ but no calib_cam_to_cam/"), std::string::npos) << halfPerFrame;
}

TEST_F(Kitti2015Layout, AScanFolderWithoutAnyCalibrationSaysWhichFilesWereLookedFor) {
  touch(root_ / "velodyne" / "000000.bin");  // not named as a KITTI 2015 frame: no layout at all
  touch(root_ / "image_2" / "000000.png");
  EXPECT_EQ(sequence::directoryLayout(root_.string()), sequence::Layout::KittiOdometryRoot);
  const std::string message = errorOf();
  EXPECT_NE(message.find("has no frames"), std::string::npos) << message;
  for (const char* looked : {"calib.txt", "calib/NNNNNN.txt", "calib/calib_cam_to_cam.txt", "calib_cam_to_cam/"}) {
    EXPECT_NE(message.find(looked), std::string::npos) << looked << " in " << message;
  }
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
