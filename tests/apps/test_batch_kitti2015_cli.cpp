// lidar_sgm_batch on KITTI stereo 2015's training layout with its raw scans (the paper's
// benchmark, ../shared/data/kitti2015_lidar): each frame's cloud is lidar_sgm_densify's byte for
// byte, with the shared calibration pair and with KITTI 2015's own per-frame files. The data set
// is only linked into a temporary folder, never copied; the tests skip where it is absent.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult shell(const std::string& command) {
  return test::runCommand(command + " 2>&1");
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class BatchKitti2015 : public ::testing::Test {
 protected:
  void SetUp() override {
    data_ = fs::path(test::kSharedDataDir) / "kitti2015_lidar";
    if (!fs::is_directory(data_)) GTEST_SKIP() << data_ << " is absent";
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() / ("lidar_sgm_batch_kitti2015_" + test + "_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "in");
  }
  void TearDown() override {
    if (!root_.empty()) fs::remove_all(root_);
  }

  /// `file` of the data set linked as `in/link`.
  void link(const std::string& file, const std::string& link) {
    fs::create_directories((root_ / "in" / link).parent_path());
    fs::create_symlink(data_ / file, root_ / "in" / link);
  }

  /// Frame `id`'s scan, images and ground truth in KITTI 2015's layout, and an _11 image that is
  /// no frame (the data set has none: the _10 one stands in for it).
  void linkFrame(const std::string& id) {
    for (const std::string folder : {"image_2", "image_3", "disp_occ_0", "obj_map"}) {
      link(folder + "/" + id + "_10.png", folder + "/" + id + "_10.png");
    }
    link("image_2/" + id + "_10.png", "image_2/" + id + "_11.png");
    link("velodyne/" + id + "_10.bin", "velodyne/" + id + "_10.bin");
  }

  /// lidar_sgm_densify's cloud of frame `id`, given the shared pair's calib_cam_to_cam.txt `calib`.
  std::string densified(const std::string& id, const fs::path& calib) {
    const fs::path in = root_ / "in";
    const fs::path out = root_ / ("densify_" + id + ".pcd");
    const RunResult r = shell(std::string(test::kDensifyTool) + " " + (in / "velodyne" / (id + "_10.bin")).string() +
                              " " + out.string() + " -calib " + calib.string() + " -left " +
                              (in / "image_2" / (id + "_10.png")).string() + " -right " +
                              (in / "image_3" / (id + "_10.png")).string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readText(out);
  }

  RunResult batch(const fs::path& out) {
    return shell(std::string(test::kBatchTool) + " -input_dir " + (root_ / "in").string() + " -output_dir " +
                 out.string());
  }

  fs::path data_;
  fs::path root_;
};

TEST_F(BatchKitti2015, SharedCalibrationGivesLidarSgmDensifysCloudOfEveryScannedFrame) {
  const std::vector<std::string> ids{"000007", "000012"};
  for (const std::string& id : ids) linkFrame(id);
  link("calib/calib_cam_to_cam.txt", "calib/calib_cam_to_cam.txt");
  link("calib/calib_velo_to_cam.txt", "calib/calib_velo_to_cam.txt");
  const fs::path out = root_ / "out";
  const RunResult r = batch(out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(": KITTI stereo 2015 training, 2 frame(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Summary: 2/2 frames: 2 ok, 0 skipped, 0 failed"), std::string::npos) << r.output;
  for (const std::string& id : ids) {
    const std::string cloud = readText(out / (id + "_10.pcd"));
    ASSERT_FALSE(cloud.empty()) << id;
    EXPECT_TRUE(cloud == densified(id, root_ / "in" / "calib" / "calib_cam_to_cam.txt"))
        << id << "_10 differs from lidar_sgm_densify's";
    EXPECT_FALSE(fs::exists(out / (id + "_11.pcd"))) << "an _11 image is no frame";
  }
}

// KITTI 2015's own files (calib_cam_to_cam/000007.txt, calib_velo_to_cam/000007.txt) hold the
// same day's calibration here: the same cloud as from the shared pair.
TEST_F(BatchKitti2015, PerFrameCalibrationGivesTheSameCloud) {
  linkFrame("000007");
  link("calib/calib_cam_to_cam.txt", "calib_cam_to_cam/000007.txt");
  link("calib/calib_velo_to_cam.txt", "calib_velo_to_cam/000007.txt");
  const fs::path out = root_ / "out";
  const RunResult r = batch(out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(": KITTI stereo 2015 training, 1 frame(s)"), std::string::npos) << r.output;
  const std::string cloud = readText(out / "000007_10.pcd");
  ASSERT_FALSE(cloud.empty());
  EXPECT_TRUE(cloud == densified("000007", data_ / "calib" / "calib_cam_to_cam.txt"))
      << "differs from lidar_sgm_densify's";
}

}  // namespace
}  // namespace lidar_sgm
