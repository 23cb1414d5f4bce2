#pragma once
// The fixture of lidar_sgm_batch -map's tests: a fresh temporary folder per test, and the message
// of a std::invalid_argument. Shared by their files rather than copied into each: GoogleTest
// requires every test of a suite (MapPieces) to use one fixture class.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace lidar_sgm {
namespace apps {

class MapPieces : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("lidar_sgm_map_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(getpid()));
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_);
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  std::string write(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
  }

  /// The message of what `f` throws as std::invalid_argument ("" when it does not).
  template <typename F>
  static std::string errorOf(F f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }

  std::filesystem::path root_;
};

}  // namespace apps
}  // namespace lidar_sgm
