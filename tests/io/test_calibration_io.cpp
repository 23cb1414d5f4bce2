#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/test_data.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;
using geometry::StereoCalibration;

// --- helpers -------------------------------------------------------------------------------

/// Runs `read`, expects std::runtime_error whose message contains every piece.
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

/// A synthetic, valid KITTI object-format file, one entry per line (line i+1 = entry i), with
/// keys the reader must ignore (P0, calib_time with a non-numeric value) and a blank line.
/// fx = 700, baseline = (0 - (-350)) / 700 = 0.5 m, R0 = I, Tr = the LiDAR->camera axis swap.
std::vector<std::string> syntheticObjectLines() {
  return {
      "P0: 700 0 600 0 0 700 180 0 0 0 1 0",                    // line 1
      "P2: 700 0 600 0 0 700 180 0 0 0 1 0",                    // line 2
      "P3: 700 0 600 -350 0 700 180 0 0 0 1 0",                 // line 3
      "R0_rect: 1 0 0 0 1 0 0 0 1",                             // line 4
      "Tr_velo_to_cam: 0 -1 0 0.1 0 0 -1 0.2 1 0 0 0.3",        // line 5
      "",                                                       // line 6
      "calib_time: 09-Jan-2012 13:57:47",                       // line 7
  };
}

const char* kSyntheticCamToCam =
    "calib_time: 09-Jan-2012 13:57:47\n"
    "S_rect_02: 1.000000e+02 5.000000e+01\n"
    "R_rect_00: 1 0 0 0 1 0 0 0 1\n"
    "P_rect_02: 700 0 600 0 0 700 180 0 0 0 1 0\n"
    "P_rect_03: 700 0 600 -350 0 700 180 0 0 0 1 0\n";
const char* kSyntheticVeloToCam =
    "calib_time: 15-Mar-2012 11:37:16\n"
    "R: 0 -1 0 0 0 -1 1 0 0\n"
    "T: 0.1 0.2 0.3\n";

/// An independent, minimal reader of KITTI "KEY: numbers" lines, for hand computations.
std::vector<double> kittiNumbers(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + ":", 0) != 0) continue;
    std::istringstream values(line.substr(key.size() + 1));
    std::vector<double> out;
    for (double v; values >> v;) out.push_back(v);
    return out;
  }
  ADD_FAILURE() << key << " not in " << path;
  return {};
}

Eigen::Matrix4d padded(const std::vector<double>& v, int rows, int cols) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) m(r, c) = v.at(static_cast<std::size_t>(r * cols + c));
  }
  return m;
}

double maxAbsDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

class CalibrationIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_calib_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  std::string writeLines(const std::string& name, const std::vector<std::string>& lines) const {
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    return write(name, text);
  }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

const std::string kObjectFolder = "kitti_stereo_lidar_calib_nogt";
const std::string kRawFolder = "kitti_raw_calib_2011_09_26";
std::string objectFile(const std::string& name) { return test::sharedDataRoot() + "/" + kObjectFolder + "/calib/" + name; }
std::string rawDir() { return test::sharedDataRoot() + "/" + kRawFolder; }

// --- real KITTI files ----------------------------------------------------------------------

TEST_F(CalibrationIo, ObjectFormatRealFileGivesKittiBaselineIntrinsicsAndTranslation) {
  if (!test::haveSharedData(kObjectFolder)) GTEST_SKIP() << "no " << kObjectFolder;
  const StereoCalibration c = io::readKittiCalibration(objectFile("stereo_rcnn_demo.txt"));
  EXPECT_EQ(c.width, 0);  // object format has no size; none given
  EXPECT_EQ(c.height, 0);
  // P2 = [721.5377 0 609.5593 44.85728; 0 721.5377 172.854 0.2163791; 0 0 1 0.002745884].
  EXPECT_EQ(c.fx(), 7.215377e+02);
  EXPECT_EQ(c.fy(), 7.215377e+02);
  EXPECT_EQ(c.cx(), 6.095593e+02);
  EXPECT_EQ(c.cy(), 1.728540e+02);
  EXPECT_EQ(c.K(0, 1), 0.0);
  EXPECT_EQ(c.K(2, 2), 1.0);
  // baseline = (P2[0,3] - P3[0,3]) / fx = (44.85728 + 339.5242) / 721.5377 = 384.38148 / 721.5377
  //          = 0.532725 m. (The 0.537 m of KITTI's gray pair is P1: 387.5744 / 721.5377 = 0.53715.)
  EXPECT_NEAR(c.baseline, 0.532725, 1e-3);
  EXPECT_NEAR(c.baseline, 384.38148 / 721.5377, 1e-9);
  // t = t2 + R0 * t_tr, t2 = K^-1 P2[:,3]; z by hand (K's last row is 0 0 1, so t2z = P2[2,3]):
  //   (R0 t_tr)_z = 7.402527e-3 * -4.069766e-3 + 4.351614e-3 * -7.631618e-2 + 0.9999631 * -0.2717806
  //               = -3.0127e-5 - 3.32099e-4 - 0.2717706 = -0.2721328
  //   t_z = 0.002745884 - 0.2721328 = -0.2693869 m
  // x by hand: t2x = (44.85728 - 609.5593 * 0.002745884) / 721.5377 = 43.18350 / 721.5377 = 0.0598493,
  //   (R0 t_tr)_x = 0.9999239 * -4.069766e-3 + 9.83776e-3 * -7.631618e-2 + -7.445048e-3 * -0.2717806
  //               = -0.00406946 - 0.00075078 + 0.00202342 = -0.00279682, t_x = 0.0570525 m
  const Eigen::Vector3d t = c.T_cam_lidar.translation();
  EXPECT_NEAR(t.z(), -0.2693869, 2e-6);
  EXPECT_NEAR(t.x(), 0.0570525, 2e-6);
  const Eigen::Matrix3d R = c.T_cam_lidar.linear();
  EXPECT_LT(maxAbsDiff(R.transpose() * R, Eigen::Matrix3d::Identity()), 1e-5);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-5);
  std::cout << "[ info ] " << geometry::describe(c) << "\n";

  // The second frame's file is byte-identical: same result; a given size is kept.
  const StereoCalibration sized = io::readKittiCalibration(objectFile("densedepthmap_0000000001.txt"), 1242, 375);
  EXPECT_EQ(sized.width, 1242);
  EXPECT_EQ(sized.height, 375);
  EXPECT_EQ(maxAbsDiff(sized.T_cam_lidar.matrix(), c.T_cam_lidar.matrix()), 0.0);
}

TEST_F(CalibrationIo, RawFormatRealFilesEqualObjectFormat) {
  if (!test::haveSharedData(kObjectFolder) || !test::haveSharedData(kRawFolder)) GTEST_SKIP() << "no KITTI calib";
  const StereoCalibration object = io::readKittiCalibration(objectFile("stereo_rcnn_demo.txt"));
  const StereoCalibration raw =
      io::readKittiRawCalibration(rawDir() + "/calib_cam_to_cam.txt", rawDir() + "/calib_velo_to_cam.txt");
  EXPECT_EQ(raw.width, 1242);  // S_rect_02: 1.242000e+03 3.750000e+02
  EXPECT_EQ(raw.height, 375);
  EXPECT_EQ(raw.K, object.K);
  EXPECT_NEAR(raw.baseline, object.baseline, 1e-9);
  EXPECT_LT(maxAbsDiff(raw.T_cam_lidar.matrix(), object.T_cam_lidar.matrix()), 1e-9);
}

TEST_F(CalibrationIo, ComposedTransformProjectsLikeKittiP2R0Tr) {
  if (!test::haveSharedData(kObjectFolder)) GTEST_SKIP() << "no " << kObjectFolder;
  const std::string file = objectFile("stereo_rcnn_demo.txt");
  const StereoCalibration c = io::readKittiCalibration(file);
  // KITTI's own recipe, x = P2 * R0_rect * Tr_velo_to_cam * X, with R0/Tr padded to 4x4.
  const Eigen::Matrix<double, 3, 4> P2 = padded(kittiNumbers(file, "P2"), 3, 4).topRows<3>();
  const Eigen::Matrix4d R0 = padded(kittiNumbers(file, "R0_rect"), 3, 3);
  const Eigen::Matrix4d Tr = padded(kittiNumbers(file, "Tr_velo_to_cam"), 3, 4);
  for (const Eigen::Vector4d& X : {Eigen::Vector4d(12.0, 2.5, -1.2, 1.0), Eigen::Vector4d(40.0, -8.0, 0.5, 1.0)}) {
    const Eigen::Vector3d kitti = P2 * R0 * Tr * X;
    const Eigen::Vector3d cam = c.T_cam_lidar * X.head<3>();
    const Eigen::Vector3d ours = c.K * cam;
    ASSERT_GT(cam.z(), 1.0);
    EXPECT_NEAR(ours.x() / ours.z(), kitti.x() / kitti.z(), 1e-9);
    EXPECT_NEAR(ours.y() / ours.z(), kitti.y() / kitti.z(), 1e-9);
    // Without the t2 term (camera 2 is ~6 cm from camera 0) u would be off by ~fx*0.06/z px.
    const Eigen::Vector3d noOffset = c.K * (R0 * Tr * X).head<3>();
    EXPECT_GT(std::abs(noOffset.x() / noOffset.z() - kitti.x() / kitti.z()), 0.5);
  }
}

// --- synthetic files, formats ----------------------------------------------------------------

TEST_F(CalibrationIo, SyntheticObjectFileIgnoresUnknownKeysAndComposes) {
  const StereoCalibration c = io::readKittiCalibration(writeLines("calib.txt", syntheticObjectLines()), 640, 480);
  EXPECT_EQ(c.fx(), 700.0);
  EXPECT_EQ(c.cx(), 600.0);
  EXPECT_EQ(c.cy(), 180.0);
  EXPECT_DOUBLE_EQ(c.baseline, 0.5);  // 350 / 700
  // R0 = I, t2 = 0: T = Tr; LiDAR x (forward) -> camera z.
  const Eigen::Vector3d p = c.T_cam_lidar * Eigen::Vector3d(10.0, 0.0, 0.0);
  EXPECT_EQ(p, Eigen::Vector3d(0.1, 0.2, 10.3));
}

TEST_F(CalibrationIo, YamlRoundTripIsExactAndLeavesNoTemporary) {
  StereoCalibration c;
  c.width = 1242;
  c.height = 375;
  c.K << 721.5377, 0.0, 609.5593, 0.0, 721.5377, 172.854, 0.0, 0.0, 1.0;
  c.baseline = 384.38148 / 721.5377;  // not representable in few digits: tests full precision
  c.T_cam_lidar = Eigen::Translation3d(0.0570525, -0.07, -0.2693869) *
                  Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 2.0, 3.0).normalized());
  const std::string file = path("calib.yaml");
  io::writeCalibrationYaml(file, c);
  EXPECT_TRUE(fs::is_regular_file(file));
  EXPECT_EQ(fileCount(), 1u);  // no hidden temporary beside it
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("%YAML", 0), 0u) << text;  // YAML chosen from the .yaml extension
  EXPECT_NE(text.find("# lidar_sgm"), std::string::npos) << text;
  const StereoCalibration back = io::readCalibrationYaml(file);
  EXPECT_EQ(back.width, c.width);
  EXPECT_EQ(back.height, c.height);
  EXPECT_EQ(back.K, c.K);
  EXPECT_EQ(back.baseline, c.baseline);
  EXPECT_LE(maxAbsDiff(back.T_cam_lidar.matrix(), c.T_cam_lidar.matrix()), 1e-12);
}

TEST_F(CalibrationIo, YamlWriteIntoMissingDirectoryThrowsAndLeavesNothing) {
  StereoCalibration c;
  c.width = 10;
  c.height = 10;
  c.baseline = 0.5;
  const fs::path missing = dir_ / "missing";
  expectErrorContaining([&] { io::writeCalibrationYaml((missing / "calib.yaml").string(), c); },
                        {(missing / "calib.yaml").string()});
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_EQ(fileCount(), 0u);
  // An invalid calibration (no size) is refused before anything is written.
  c.width = 0;
  EXPECT_THROW(io::writeCalibrationYaml(path("c.yaml"), c), std::invalid_argument);
  EXPECT_EQ(fileCount(), 0u);
}

TEST_F(CalibrationIo, ReadCalibrationDispatchesOnThePath) {
  // .yaml -> YAML (the size arguments are ignored)
  StereoCalibration yaml;
  yaml.width = 321;
  yaml.height = 123;
  yaml.baseline = 0.25;
  io::writeCalibrationYaml(path("c.yaml"), yaml);
  EXPECT_EQ(io::readCalibration(path("c.yaml"), 5, 5).width, 321);
  // a directory -> raw (size from S_rect_02: 100x50); a calib_cam_to_cam.txt path -> raw
  fs::create_directories(dir_ / "raw");
  write("raw/calib_cam_to_cam.txt", kSyntheticCamToCam);
  write("raw/calib_velo_to_cam.txt", kSyntheticVeloToCam);
  const StereoCalibration fromDir = io::readCalibration((dir_ / "raw").string());
  EXPECT_EQ(fromDir.width, 100);
  EXPECT_EQ(fromDir.height, 50);
  EXPECT_DOUBLE_EQ(fromDir.baseline, 0.5);
  EXPECT_EQ(io::readCalibration(path("raw/calib_cam_to_cam.txt")).width, 100);
  // any other file -> object format, with the given size
  const StereoCalibration object = io::readCalibration(writeLines("000000.txt", syntheticObjectLines()), 640, 480);
  EXPECT_EQ(object.width, 640);
  EXPECT_EQ(object.K, fromDir.K);
  EXPECT_EQ(object.T_cam_lidar.matrix(), fromDir.T_cam_lidar.matrix());
  // a raw directory without its velo file names the missing file
  fs::remove(dir_ / "raw" / "calib_velo_to_cam.txt");
  expectErrorContaining([&] { io::readCalibration((dir_ / "raw").string()); },
                        {"calib_velo_to_cam.txt", "no such file"});

  if (test::haveSharedData(kObjectFolder) && test::haveSharedData(kRawFolder)) {
    const StereoCalibration realRaw = io::readCalibration(rawDir());
    const StereoCalibration realRawFile = io::readCalibration(rawDir() + "/calib_cam_to_cam.txt");
    const StereoCalibration realObject = io::readCalibration(objectFile("stereo_rcnn_demo.txt"), 1242, 375);
    EXPECT_EQ(realRaw.width, 1242);
    EXPECT_EQ(realRawFile.T_cam_lidar.matrix(), realRaw.T_cam_lidar.matrix());
    EXPECT_EQ(realObject.width, 1242);
    EXPECT_LT(maxAbsDiff(realObject.T_cam_lidar.matrix(), realRaw.T_cam_lidar.matrix()), 1e-9);
  }
}

// --- errors --------------------------------------------------------------------------------

TEST_F(CalibrationIo, MissingFileIsNamed) {
  const std::string missing = path("nope.txt");
  expectErrorContaining([&] { io::readKittiCalibration(missing); },
                        {"cannot read calibration '" + missing + "'", "no such file"});
  expectErrorContaining([&] { io::readCalibrationYaml(path("nope.yaml")); }, {"nope.yaml", "no such file"});
}

TEST_F(CalibrationIo, MissingKeyNamesFileAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines.erase(lines.begin() + 3);  // R0_rect
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ": missing key 'R0_rect'"});
  write("velo.txt", "R: 1 0 0 0 1 0 0 0 1\n");  // no T
  const std::string cam = write("cam.txt", kSyntheticCamToCam);
  expectErrorContaining([&] { io::readKittiRawCalibration(cam, path("velo.txt")); },
                        {path("velo.txt") + ": missing key 'T'"});
}

TEST_F(CalibrationIo, MalformedNumberNamesFileLineAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[1] = "P2: 7.2e+02 0 abc 0 0 700 180 0 0 0 1 0";
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":2: key 'P2'", "malformed", "'abc'"});
  lines[1] = "P2: 700 0 600x 0 0 700 180 0 0 0 1 0";  // a number with trailing junk
  writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":2: key 'P2'", "'600x'"});
}

TEST_F(CalibrationIo, TooFewNumbersNamesFileLineAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[2] = "P3: 700 0 600 -350 0 700 180 0 0 0 1";  // 11 numbers
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); },
                        {file + ":3: key 'P3': expected 12 numbers, got 11"});
  std::string cam = kSyntheticCamToCam;
  cam.replace(cam.find("S_rect_02: 1.000000e+02 5.000000e+01"), 36, "S_rect_02: 1.000000e+02");
  write("cam.txt", cam);
  write("velo.txt", kSyntheticVeloToCam);
  expectErrorContaining([&] { io::readKittiRawCalibration(path("cam.txt"), path("velo.txt")); },
                        {path("cam.txt") + ":2: key 'S_rect_02': expected 2 numbers, got 1"});
}

TEST_F(CalibrationIo, NonFiniteNumberNamesFileLineAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[1] = "P2: 700 0 600 nan 0 700 180 0 0 0 1 0";
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":2: key 'P2'", "non-finite", "'nan'"});
  lines[1] = "P2: 700 0 600 0 0 700 180 0 0 0 1 0";
  lines[4] = "Tr_velo_to_cam: 0 -1 0 inf 0 0 -1 0.2 1 0 0 0.3";
  writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":5: key 'Tr_velo_to_cam'", "'inf'"});
}

TEST_F(CalibrationIo, NonOrthonormalRotationNamesFileLineAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[4] = "Tr_velo_to_cam: 0 -1.1 0 0.1 0 0 -1.1 0.2 1.1 0 0 0.3";  // rotation * 1.1
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); },
                        {file + ":5: key 'Tr_velo_to_cam'", "not a rotation"});
  lines = syntheticObjectLines();
  lines[3] = "R0_rect: 1.1 0 0 0 1.1 0 0 0 1.1";
  writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":4: key 'R0_rect'", "not a rotation"});
}

TEST_F(CalibrationIo, ZeroBaselineNamesFileAndKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[2] = "P3: 700 0 600 0 0 700 180 0 0 0 1 0";  // P3 = P2
  const std::string file = writeLines("calib.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(file); }, {file + ":3: key 'P3'", "baseline"});
}

TEST_F(CalibrationIo, InvalidSizeIsReportedWithTheFile) {
  // A given size is validated; the other checks run even without one (above: rotation, baseline).
  const std::string file = writeLines("calib.txt", syntheticObjectLines());
  expectErrorContaining([&] { io::readKittiCalibration(file, -5, 10); }, {"invalid calibration '" + file + "'", "size"});
}

TEST_F(CalibrationIo, YamlMissingKeyNamesFileAndKey) {
  const std::string file = write("calib.yaml",
                                 "%YAML:1.0\n---\nwidth: 10\nheight: 10\n"
                                 "K: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                                 "   data: [ 700., 0., 5., 0., 700., 5., 0., 0., 1. ]\n"
                                 "T_cam_lidar: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
                                 "   data: [ 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1. ]\n");
  expectErrorContaining([&] { io::readCalibrationYaml(file); }, {file + ": missing key 'baseline'"});
}

TEST_F(CalibrationIo, YamlSyntaxErrorBecomesRuntimeErrorNamingTheFile) {
  const std::string file = write("calib.yaml", "%YAML:1.0\n---\nwidth: [ 1, 2\nheight: }}: {{\n  - : :\n");
  expectErrorContaining([&] { io::readCalibrationYaml(file); }, {"'" + file + "'", "syntax"});
}

TEST_F(CalibrationIo, FocalLengthAndBaselineOutsideTheirSaneRangesNameTheKey) {
  std::vector<std::string> lines = syntheticObjectLines();
  lines[1] = "P2: 1e-300 0 600 0 0 700 180 0 0 0 1 0";  // a 3.8e302 m baseline followed
  lines[2] = "P3: 1e-300 0 600 -350 0 700 180 0 0 0 1 0";
  const std::string tiny = writeLines("tiny.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(tiny, 640, 480); }, {tiny + ":2: key 'P2'", "[1, 1000000] px"});
  lines = syntheticObjectLines();
  lines[2] = "P3: 700 0 600 -350000 0 700 180 0 0 0 1 0";  // 500 m
  const std::string wide = writeLines("wide.txt", lines);
  expectErrorContaining([&] { io::readKittiCalibration(wide, 640, 480); }, {wide + ":3: key 'P3'", "[0.001, 100] m"});
}

TEST_F(CalibrationIo, YamlOutsideTheSaneRangesNamesTheFile) {
  const std::string file = write("calib.yaml",
                                 "%YAML:1.0\n---\nwidth: 10\nheight: 10\n"
                                 "K: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                                 "   data: [ 700., 0., 5., 0., 700., 5., 0., 0., 1. ]\nbaseline: 1e5\n"
                                 "T_cam_lidar: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
                                 "   data: [ 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1. ]\n");
  expectErrorContaining([&] { io::readCalibrationYaml(file); }, {"'" + file + "'", "baseline must lie in"});
}

TEST_F(CalibrationIo, YamlMatrixOfTheWrongShapeOrNonFiniteNamesTheKey) {
  const std::string head = "%YAML:1.0\n---\nwidth: 10\nheight: 10\nbaseline: 0.5\n"
                           "T_cam_lidar: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
                           "   data: [ 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1. ]\n";
  const std::string shape = write("shape.yaml", head + "K: !!opencv-matrix\n   rows: 100000\n   cols: 100000\n"
                                                       "   dt: d\n   data: [ 1. ]\n");
  expectErrorContaining([&] { io::readCalibrationYaml(shape); }, {shape + ": key 'K'", "3x3"});
  const std::string nan = write("nan.yaml", head + "K: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                                                   "   data: [ 700., 0., 5., 0., .nan, 5., 0., 0., 1. ]\n");
  expectErrorContaining([&] { io::readCalibrationYaml(nan); }, {nan + ": key 'K'", "data value 5"});
  const std::string deep = write("deep.yaml", "%YAML:1.0\n---\nK: " + std::string(5000, '[') + "\n");
  expectErrorContaining([&] { io::readCalibrationYaml(deep); }, {"'" + deep + "'", "syntax"});
}

}  // namespace
}  // namespace lidar_sgm
