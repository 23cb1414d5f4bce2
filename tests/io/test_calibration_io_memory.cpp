// Calibration readers from memory (strings, streams): the same results as the path readers on
// the same text, and errors that name the caller's label instead of a file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "common/test_data.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;
using geometry::StereoCalibration;

void expectErrorContaining(const std::function<void()>& read, std::initializer_list<std::string> pieces) {
  try {
    read();
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    for (const std::string& piece : pieces) {
      EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
    }
  }
}

/// Bit-for-bit equality: the memory and path readers run the same parser on the same bytes.
void expectIdentical(const StereoCalibration& a, const StereoCalibration& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.K, b.K);
  EXPECT_EQ(a.baseline, b.baseline);
  EXPECT_EQ(a.T_cam_lidar.matrix(), b.T_cam_lidar.matrix());
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// fx = 700, baseline = 350 / 700 = 0.5 m; a non-trivial R0 and Tr so that every term counts.
const std::string kObjectText =
    "P0: 700 0 600 0 0 700 180 0 0 0 1 0\n"
    "P2: 700 0 600 44.8 0 700 180 0.2 0 0 1 0.0027\n"
    "P3: 700 0 600 -305.2 0 700 180 0.2 0 0 1 0.0027\n"
    "R0_rect: 0.9999239 0.00983776 -0.007445048 -0.009869795 0.9999421 -0.004278459 0.007402527 0.004351614 0.9999631\n"
    "Tr_velo_to_cam: 0 -1 0 0.1 0 0 -1 0.2 1 0 0 0.3\n"
    "calib_time: 09-Jan-2012 13:57:47\n";
const std::string kCamToCamText =
    "calib_time: 09-Jan-2012 13:57:47\n"
    "S_rect_02: 1.000000e+02 5.000000e+01\n"
    "R_rect_00: 1 0 0 0 1 0 0 0 1\n"
    "P_rect_02: 700 0 600 0 0 700 180 0 0 0 1 0\n"
    "P_rect_03: 700 0 600 -350 0 700 180 0 0 0 1 0\n";
const std::string kVeloToCamText =
    "calib_time: 15-Mar-2012 11:37:16\n"
    "R: 0 -1 0 0 0 -1 1 0 0\n"
    "T: 0.1 0.2 0.3\n";

class CalibrationMemory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_calib_mem_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string file = (dir_ / name).string();
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  fs::path dir_;
};

// --- KITTI object ----------------------------------------------------------------------------

TEST_F(CalibrationMemory, KittiObjectStringAndStreamEqualThePathReader) {
  const std::string file = write("calib.txt", kObjectText);
  const StereoCalibration fromFile = io::readKittiCalibration(file, 640, 480);
  expectIdentical(io::readKittiCalibrationFromString(kObjectText, "<string>", 640, 480), fromFile);
  std::istringstream stream(kObjectText);
  expectIdentical(io::readKittiCalibration(stream, "calib stream", 640, 480), fromFile);
  // Not a vacuous equality: the text composes to what the header promises.
  EXPECT_EQ(fromFile.fx(), 700.0);
  EXPECT_DOUBLE_EQ(fromFile.baseline, 350.0 / 700.0);
  EXPECT_EQ(io::readKittiCalibrationFromString(kObjectText).width, 0);  // size unknown by default
}

TEST_F(CalibrationMemory, KittiObjectRealFileTextEqualsThePathReader) {
  const std::string folder = "kitti_stereo_lidar_calib_nogt";
  if (!test::haveSharedData(folder)) GTEST_SKIP() << "no " << folder;
  const std::string file = test::sharedDataRoot() + "/" + folder + "/calib/stereo_rcnn_demo.txt";
  expectIdentical(io::readKittiCalibrationFromString(fileText(file), file, 1242, 375),
                  io::readKittiCalibration(file, 1242, 375));
}

TEST_F(CalibrationMemory, KittiObjectErrorsNameTheCallersLabelLineAndKey) {
  std::string malformed = kObjectText;
  malformed.replace(malformed.find("44.8"), 4, "4x.8");
  expectErrorContaining([&] { io::readKittiCalibrationFromString(malformed, "frame 7 calib"); },
                        {"frame 7 calib:2: key 'P2'", "malformed number '4x.8'"});
  std::istringstream stream(malformed);
  expectErrorContaining([&] { io::readKittiCalibration(stream, "frame 8 calib"); }, {"frame 8 calib:2: key 'P2'"});
  // The default label, for a missing key and for a line that is no "KEY: values".
  expectErrorContaining([&] { io::readKittiCalibrationFromString("P2: 700 0 600 0 0 700 180 0 0 0 1 0\n"); },
                        {"<string>: missing key 'P3'"});
  expectErrorContaining([&] { io::readKittiCalibrationFromString("P2 700 0\n"); },
                        {"<string>:1: expected 'KEY: values'"});
  // Binary data (a scan or an image given as the calibration) is named as such, even when its
  // first line would pass for text (a PNG's "\x89PNG" line), and its bytes are not echoed.
  expectErrorContaining([&] { io::readKittiCalibrationFromString(std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "image"); },
                        {"cannot read calibration 'image'", "looks binary"});
  // validate() failures name the source too.
  expectErrorContaining([&] { io::readKittiCalibrationFromString(kObjectText, "mem", -5, 10); },
                        {"invalid calibration 'mem'", "size"});
}

// --- KITTI raw -------------------------------------------------------------------------------

TEST_F(CalibrationMemory, KittiRawStringsAndStreamsEqualThePathReader) {
  const std::string cam = write("calib_cam_to_cam.txt", kCamToCamText);
  const std::string velo = write("calib_velo_to_cam.txt", kVeloToCamText);
  const StereoCalibration fromFiles = io::readKittiRawCalibration(cam, velo);
  expectIdentical(io::readKittiRawCalibrationFromString(kCamToCamText, kVeloToCamText), fromFiles);
  std::istringstream camStream(kCamToCamText);
  std::istringstream veloStream(kVeloToCamText);
  expectIdentical(io::readKittiRawCalibration(camStream, "cam", veloStream, "velo"), fromFiles);
  EXPECT_EQ(fromFiles.width, 100);
  EXPECT_EQ(fromFiles.height, 50);
}

TEST_F(CalibrationMemory, KittiRawRealFilesTextEqualsThePathReader) {
  const std::string folder = "kitti_raw_calib_2011_09_26";
  if (!test::haveSharedData(folder)) GTEST_SKIP() << "no " << folder;
  const std::string cam = test::sharedDataRoot() + "/" + folder + "/calib_cam_to_cam.txt";
  const std::string velo = test::sharedDataRoot() + "/" + folder + "/calib_velo_to_cam.txt";
  expectIdentical(io::readKittiRawCalibrationFromString(fileText(cam), fileText(velo)),
                  io::readKittiRawCalibration(cam, velo));
}

TEST_F(CalibrationMemory, KittiRawErrorsNameTheTextAtFault) {
  // Each text's own label: a bad velo_to_cam text must not be blamed on cam_to_cam.
  expectErrorContaining([&] { io::readKittiRawCalibrationFromString(kCamToCamText, "R: 0 -1 0\nT: 1 2 3\n"); },
                        {"<calib_velo_to_cam string>:1: key 'R'", "expected 9 numbers, got 3"});
  std::string noSize = kCamToCamText;
  noSize.erase(noSize.find("S_rect_02"), noSize.find("R_rect_00") - noSize.find("S_rect_02"));
  std::istringstream camStream(noSize);
  std::istringstream veloStream(kVeloToCamText);
  expectErrorContaining([&] { io::readKittiRawCalibration(camStream, "cam text", veloStream, "velo text"); },
                        {"cam text: missing key 'S_rect_02'"});
}

// --- YAML ------------------------------------------------------------------------------------

StereoCalibration yamlCalibration() {
  StereoCalibration c;
  c.width = 1242;
  c.height = 375;
  c.K << 721.5377, 0.0, 609.5593, 0.0, 721.5377, 172.854, 0.0, 0.0, 1.0;
  c.baseline = 384.38148 / 721.5377;
  c.T_cam_lidar = Eigen::Translation3d(0.0570525, -0.07, -0.2693869) *
                  Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized());
  return c;
}

TEST_F(CalibrationMemory, KittiRawRigidTransformIsRThenT) {
  // calib_imu_to_velo.txt's form: a quarter turn about z, then the offset.
  std::istringstream in("calib_time: 25-May-2012 16:47:16\nR: 0 -1 0 1 0 0 0 0 1\nT: -0.81 0.32 -0.8\n");
  const Eigen::Isometry3d imuToVelo = io::readKittiRawRigidTransform(in, "<imu_to_velo>");
  EXPECT_TRUE((imuToVelo * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(-0.81, 1.32, -0.8)));
  EXPECT_EQ(imuToVelo.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
  std::istringstream noT("R: 1 0 0 0 1 0 0 0 1\n");
  expectErrorContaining([&] { io::readKittiRawRigidTransform(noT, "<imu_to_velo>"); },
                        {"<imu_to_velo>", "missing key 'T'"});
  std::istringstream sheared("R: 1 0.1 0 0 1 0 0 0 1\nT: 0 0 0\n");
  expectErrorContaining([&] { io::readKittiRawRigidTransform(sheared, "<imu_to_velo>"); },
                        {"<imu_to_velo>:1: key 'R'", "not a rotation"});
  expectErrorContaining([] { io::readKittiRawRigidTransform("/no/such/calib_imu_to_velo.txt"); },
                        {"/no/such/calib_imu_to_velo.txt", "no such file"});
}

TEST_F(CalibrationMemory, YamlStringAndStreamEqualThePathReader) {
  const std::string file = (dir_ / "calib.yaml").string();
  io::writeCalibrationYaml(file, yamlCalibration());
  const std::string text = fileText(file);
  const StereoCalibration fromFile = io::readCalibrationYaml(file);
  expectIdentical(io::readCalibrationYamlFromString(text), fromFile);
  std::istringstream stream(text);
  expectIdentical(io::readCalibrationYaml(stream, "yaml stream"), fromFile);
  EXPECT_EQ(fromFile.width, 1242);
  EXPECT_EQ(fromFile.baseline, yamlCalibration().baseline);
}

TEST_F(CalibrationMemory, YamlErrorsNameTheCallersLabel) {
  expectErrorContaining([&] { io::readCalibrationYamlFromString("%YAML:1.0\n---\nwidth: [ 1, 2\nheight: }}: {{\n"); },
                        {"'<string>'", "syntax"});
  std::istringstream stream("%YAML:1.0\n---\nwidth: 10\nheight: 10\n");
  expectErrorContaining([&] { io::readCalibrationYaml(stream, "yaml@memory"); }, {"yaml@memory: missing key 'K'"});
  expectErrorContaining([&] { io::readCalibrationYamlFromString("%YAML:1.0\n---\nwidth: ten\n", "w"); },
                        {"w: key 'width': expected an integer"});
  expectErrorContaining([&] { io::readCalibrationYamlFromString("  \n", "blank"); }, {"'blank'", "empty"});
  expectErrorContaining([&] { io::readCalibrationYamlFromString(std::string("%YAML:1.0\n\0x", 12), "nul"); },
                        {"'nul'", "NUL"});
}

}  // namespace
}  // namespace lidar_sgm
