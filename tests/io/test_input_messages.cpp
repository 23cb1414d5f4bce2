// What the readers say when they are handed the wrong thing: a folder for a file, a file they may
// not open, a LiDAR scan for a calibration, another KITTI file than the one they read. The message
// must name what was found and what is accepted, and never carry the file's raw bytes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/file_access.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

class InputMessages : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lidar_sgm_input_messages_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_ / "locked.txt", fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }
  fs::path dir_;
};

/// The message of the std::runtime_error `read` throws ("" when it throws none).
template <typename Read>
std::string messageOf(Read&& read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected std::runtime_error";
  return "";
}

void expectContains(const std::string& message, const std::string& piece) {
  EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
}

bool printable(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f) return false;
  }
  return true;
}

const char* const kVeloToCam =
    "calib_time: 15-Mar-2012 11:37:16\n"
    "R: 7.533745e-03 -9.999714e-01 -6.166020e-04 1.480249e-02 7.280733e-04 -9.998902e-01 9.998621e-01 "
    "7.523790e-03 1.480755e-02\n"
    "T: -4.069766e-03 -7.631618e-02 -2.717806e-01\n"
    "delta_f: 0.000000e+00 0.000000e+00\n"
    "delta_c: 0.000000e+00 0.000000e+00\n";

TEST_F(InputMessages, KittiRawVeloToCamAloneNamesTheFormatsAndWhatItFound) {
  const std::string file = write("2011_09_26/calib_velo_to_cam.txt", kVeloToCam);
  const std::string message = messageOf([&] { io::readCalibration(file); });
  expectContains(message, "missing key 'P2'");
  expectContains(message, "the text has keys R, T, calib_time, delta_c, delta_f");
  expectContains(message, "looks like KITTI raw's calib_velo_to_cam.txt");
  // Every format readCalibration accepts.
  expectContains(message, "KITTI object calib file (keys P2, P3, R0_rect, Tr_velo_to_cam)");
  expectContains(message, "KITTI raw date folder");
  expectContains(message, "calib_cam_to_cam.txt with calib_velo_to_cam.txt beside it");
  expectContains(message, "YAML file (.yaml/.yml");
}

TEST_F(InputMessages, KittiRawCamToCamUnderAnotherNameIsRecognised) {
  const std::string file = write("cam.txt", "S_rect_02: 1242 375\nP_rect_02: 1 0 0 0 0 1 0 0 0 0 1 0\n");
  const std::string message = messageOf([&] { io::readCalibration(file); });
  expectContains(message, "looks like KITTI raw's calib_cam_to_cam.txt");
}

TEST_F(InputMessages, BinaryCalibrationIsNeverEchoed) {
  // A KITTI scan: float32 x y z intensity, full of NULs and bytes >= 0x80.
  std::string scan;
  for (int i = 0; i < 400; ++i) {
    const float values[4] = {10.5f + static_cast<float>(i), -2.25f, 0.0f, 0.5f};
    scan.append(reinterpret_cast<const char*>(values), sizeof values);
  }
  const std::string file = write("velodyne/000000.bin", scan);
  const std::string message = messageOf([&] { io::readCalibration(file); });
  expectContains(message, "cannot read calibration '" + file + "': the file looks binary (6400 bytes");
  expectContains(message, "KITTI object calib file");
  EXPECT_TRUE(printable(message)) << message;
  EXPECT_LT(message.size(), 1000u) << message;
  // Text with a few stray bytes is not binary, but its quoted line is escaped and short.
  const std::string garbled = write("garbled.txt", "P2 \x1b[31m" + std::string(300, 'x') + "\n");
  const std::string line = messageOf([&] { io::readCalibration(garbled); });
  expectContains(line, ":1: expected 'KEY: values', got 'P2 \\x1b[31m");
  EXPECT_TRUE(printable(line)) << line;
  EXPECT_LT(line.size(), 1000u) << line;
}

TEST_F(InputMessages, DirectoryIsCalledADirectory) {
  const std::string folder = (dir_ / "image_2").string();
  fs::create_directories(folder);
  expectContains(messageOf([&] { io::readImage(folder); }),
                 "cannot read image '" + folder + "': it is a directory, not a file");
  expectContains(messageOf([&] { io::readKittiCalibration(folder); }),
                 "cannot read calibration '" + folder + "': it is a directory, not a file");
  // readCalibration takes a folder for KITTI raw's: one without its files is not one.
  const std::string calibration = messageOf([&] { io::readCalibration(folder); });
  expectContains(calibration, "it is a directory without calib_cam_to_cam.txt, not a KITTI raw date folder");
  expectContains(calibration, "KITTI object calib file");
  EXPECT_EQ(io::unreadableFileReason(folder), "it is a directory, not a file");
  EXPECT_EQ(io::unreadableFileReason(folder + "/none.png"), "no such file");
  EXPECT_EQ(io::unreadableFileReason(write("ok.txt", "x")), "");
}

TEST_F(InputMessages, PermissionDeniedIsSaid) {
  const std::string file = write("locked.txt", "P2: 1\n");
  fs::permissions(file, fs::perms::none);
  if (std::ifstream(file).good()) GTEST_SKIP() << "running as root: a file without permissions still opens";
  EXPECT_EQ(io::unreadableFileReason(file), "cannot open it: Permission denied");
  expectContains(messageOf([&] { io::readImage(file); }), "cannot open it: Permission denied");
  expectContains(messageOf([&] { io::readCalibration(file); }), "cannot open it: Permission denied");
}

}  // namespace
}  // namespace lidar_sgm
