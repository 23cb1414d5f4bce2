#pragma once
// The fixture of lidar_sgm_batch's frame-list, odometry-calibration and manifest tests: a fresh
// temporary folder per test. Shared by their files rather than copied into each: GoogleTest
// requires every test of a suite (FrameList) to use one fixture class.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace lidar_sgm {
namespace apps {

class FrameList : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("lidar_sgm_frame_list_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
             "_" + std::to_string(getpid()));
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_);
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  /// An empty file (discovery reads names only).
  void touch(const std::filesystem::path& path) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << "";
  }
  void write(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
  }

  std::filesystem::path root_;
};

}  // namespace apps
}  // namespace lidar_sgm
