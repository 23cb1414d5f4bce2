// lidar_sgm_batch's pieces: frame discovery in each layout, list files, shards, the KITTI odometry
// calibration, the manifest's JSON lines and what a re-run carries over from earlier manifests.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "lidar_sgm/sequence/frame_calibration.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"
#include "lidar_sgm/sequence/manifest.hpp"
#include "batch/output_state.hpp"
#include "lidar_sgm/io/calibration_io.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
namespace fs = std::filesystem;

class FrameList : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("lidar_sgm_frame_list_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
             "_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  /// An empty file (discovery reads names only).
  void touch(const fs::path& path) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "";
  }
  void write(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
  }

  fs::path root_;
};

TEST_F(FrameList, OdometrySequenceGivesFramesInOrderWithTheirImagesWhereTheyExist) {
  const fs::path seq = root_ / "07";
  touch(seq / "calib.txt");
  for (const char* stem : {"000002", "000000", "000001"}) touch(seq / "velodyne" / (std::string(stem) + ".bin"));
  touch(seq / "image_2" / "000000.png");
  touch(seq / "image_3" / "000000.png");
  touch(seq / "image_2" / "000001.png");  // a lone left image: LiDAR-only, colored
  touch(seq / "velodyne" / "notes.txt");  // not a scan
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(seq.string());
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].name, "000000");
  EXPECT_EQ(frames[1].name, "000001");
  EXPECT_EQ(frames[2].name, "000002");
  EXPECT_EQ(frames[0].left, (seq / "image_2" / "000000.png").string());
  EXPECT_EQ(frames[0].right, (seq / "image_3" / "000000.png").string());
  EXPECT_EQ(frames[1].left, (seq / "image_2" / "000001.png").string());
  EXPECT_TRUE(frames[1].right.empty());
  EXPECT_TRUE(frames[2].left.empty());
  EXPECT_TRUE(frames[2].right.empty());
  for (const sequence::Frame& f : frames) {
    EXPECT_EQ(f.calib, (seq / "calib.txt").string());
    EXPECT_EQ(f.calibFormat, sequence::CalibrationFormat::KittiOdometry);
  }
}

TEST_F(FrameList, OdometryRootGivesEverySequenceWithItsNameInTheFrameName) {
  for (const char* seq : {"01", "00"}) {
    touch(root_ / "sequences" / seq / "calib.txt");
    touch(root_ / "sequences" / seq / "velodyne" / "000000.bin");
  }
  fs::create_directories(root_ / "poses");
  for (const fs::path& dir : {root_, root_ / "sequences"}) {
    const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(dir.string());
    ASSERT_EQ(frames.size(), 2u) << dir;
    EXPECT_EQ(frames[0].name, "00/000000");
    EXPECT_EQ(frames[1].name, "01/000000");
    EXPECT_EQ(frames[1].calib, (root_ / "sequences" / "01" / "calib.txt").string());
  }
}

TEST_F(FrameList, KittiRawDriveTakesTheCalibrationOfTheDateFolder) {
  const fs::path drive = root_ / "2011_09_26" / "2011_09_26_drive_0001_sync";
  touch(drive / "velodyne_points" / "data" / "0000000000.bin");
  touch(drive / "velodyne_points" / "data" / "0000000001.bin");
  touch(drive / "image_02" / "data" / "0000000001.png");
  touch(drive / "image_03" / "data" / "0000000001.png");
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(drive.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].name, "0000000001");
  EXPECT_TRUE(frames[0].left.empty());
  EXPECT_EQ(frames[1].right, (drive / "image_03" / "data" / "0000000001.png").string());
  EXPECT_EQ(fs::path(frames[0].calib), fs::absolute(root_ / "2011_09_26"));
  EXPECT_EQ(frames[0].calibFormat, sequence::CalibrationFormat::Auto);
}

TEST_F(FrameList, EachLayoutIsNamedAndOnlyARawDriveHasOxtsPackets) {
  const fs::path drive = root_ / "2011_09_26" / "2011_09_26_drive_0001_sync";
  touch(drive / "velodyne_points" / "data" / "0000000007.bin");
  EXPECT_EQ(sequence::directoryLayout(drive.string()), sequence::Layout::KittiRawDrive);
  EXPECT_EQ(sequence::framesFromDirectory(drive.string())[0].oxts, (drive / "oxts" / "data" / "0000000007.txt").string())
      << "the packet's path is given whether or not it exists: the map names it when it is missing";
  const fs::path object = root_ / "object";
  touch(object / "velodyne" / "000000.bin");
  touch(object / "calib" / "000000.txt");
  EXPECT_EQ(sequence::directoryLayout(object.string()), sequence::Layout::KittiObject);
  EXPECT_TRUE(sequence::framesFromDirectory(object.string())[0].oxts.empty());
  const fs::path sequenceDir = root_ / "dataset" / "sequences" / "00";
  touch(sequenceDir / "velodyne" / "000000.bin");
  touch(sequenceDir / "calib.txt");
  EXPECT_EQ(sequence::directoryLayout(sequenceDir.string()), sequence::Layout::KittiOdometrySequence);
  EXPECT_EQ(sequence::directoryLayout((root_ / "dataset").string()), sequence::Layout::KittiOdometryRoot);
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::KittiRawDrive), "KITTI raw drive");
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::KittiObject), "KITTI object layout");
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::KittiOdometrySequence), "KITTI odometry sequence");
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::KittiOdometryRoot), "KITTI odometry root");
  EXPECT_STREQ(sequence::layoutName(sequence::Layout::ListFile), "list file");
}

TEST_F(FrameList, KittiObjectLayoutTakesEachFramesCalibrationFile) {
  touch(root_ / "velodyne" / "000003.bin");
  touch(root_ / "calib" / "000003.txt");
  const std::vector<sequence::Frame> frames = sequence::framesFromDirectory(root_.string());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].calib, (root_ / "calib" / "000003.txt").string());
  EXPECT_EQ(frames[0].calibFormat, sequence::CalibrationFormat::Auto);
}

TEST_F(FrameList, AFolderOfNoKnownLayoutIsRefusedNamingTheLayouts) {
  touch(root_ / "scans" / "000000.bin");
  try {
    sequence::framesFromDirectory(root_.string());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no frames"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("KITTI raw drive"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sequence::framesFromDirectory((root_ / "missing").string()), std::invalid_argument);
}

TEST_F(FrameList, TwoScansOfOneStemAreRefused) {
  touch(root_ / "velodyne" / "000000.bin");
  touch(root_ / "velodyne" / "000000.pcd");
  touch(root_ / "calib.txt");
  EXPECT_THROW(sequence::framesFromDirectory(root_.string()), std::invalid_argument);
}

TEST_F(FrameList, ListFileResolvesRelativePathsSkipsCommentsAndTakesDashForNone) {
  write(root_ / "frames.txt",
        "# scan left right calib\n"
        "\n"
        "a/0.bin a/l0.png a/r0.png calib.txt\n"
        "  /abs/1.pcd   -   -   /abs/calib.yaml  \n"
        "a/2.bin a/l2.png - calib.txt\n");
  const std::vector<sequence::Frame> frames = sequence::framesFromList((root_ / "frames.txt").string());
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].name, "0");
  EXPECT_EQ(frames[0].scan, (root_ / "a" / "0.bin").string());
  EXPECT_EQ(frames[0].right, (root_ / "a" / "r0.png").string());
  EXPECT_EQ(frames[0].calib, (root_ / "calib.txt").string());
  EXPECT_EQ(frames[1].scan, "/abs/1.pcd");
  EXPECT_TRUE(frames[1].left.empty());
  EXPECT_TRUE(frames[1].right.empty());
  EXPECT_EQ(frames[1].calib, "/abs/calib.yaml");
  EXPECT_EQ(frames[2].left, (root_ / "a" / "l2.png").string());
  EXPECT_TRUE(frames[2].right.empty());
}

TEST_F(FrameList, BadListLinesAreRefusedNamingTheLine) {
  const auto messageOf = [&](const std::string& text) {
    write(root_ / "bad.txt", text);
    try {
      sequence::framesFromList((root_ / "bad.txt").string());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(messageOf("a.bin - - c.txt\na.bin l.png\n").find("line 2: expected SCAN LEFT RIGHT CALIB"),
            std::string::npos);
  EXPECT_NE(messageOf("a.bin - r.png c.txt\n").find("line 1: a RIGHT image needs a LEFT one"), std::string::npos);
  EXPECT_NE(messageOf("a.bin - - -\n").find("SCAN and CALIB are required"), std::string::npos);
  EXPECT_NE(messageOf("x/a.bin - - c.txt\ny/a.bin - - c.txt\n").find("line 2: a second scan named 'a'"),
            std::string::npos);
  EXPECT_NE(messageOf("# nothing\n").find("has no frames"), std::string::npos);
  EXPECT_THROW(sequence::framesFromList((root_ / "missing.txt").string()), std::invalid_argument);
}

TEST(Shard, ParsesKOverNAndRefusesAnythingElse) {
  const sequence::Shard s = sequence::parseShard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"", "2", "2/", "/5", "5/5", "-1/5", "1/0", "1/2x", "a/b", "1/2/3"}) {
    EXPECT_THROW(sequence::parseShard(bad), std::invalid_argument) << bad;
  }
}

TEST(Shard, TheShardsCoverEveryFrameExactlyOnceInOrder) {
  std::vector<sequence::Frame> frames(11);
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].name = std::to_string(i);
  for (int count : {1, 2, 3, 11, 15}) {
    std::multiset<std::string> covered;
    for (int index = 0; index < count; ++index) {
      const std::vector<sequence::Frame> mine = sequence::framesOfShard(frames, {index, count});
      for (std::size_t j = 0; j < mine.size(); ++j) {
        EXPECT_EQ(mine[j].name, std::to_string(static_cast<std::size_t>(index) + j * static_cast<std::size_t>(count)));
        covered.insert(mine[j].name);
      }
    }
    EXPECT_EQ(covered.size(), frames.size()) << count;
    for (const sequence::Frame& f : frames) EXPECT_EQ(covered.count(f.name), 1u) << count;
  }
}

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

TEST(Manifest, JsonLinesEscapeTextAndCarryEveryField) {
  EXPECT_EQ(sequence::jsonEscape("a\"b\\c\nd\te\x01"), "a\\\"b\\\\c\\nd\\te\\u0001");
  sequence::FrameRecord r;
  r.frame = "00/000001";
  r.status = "failed";
  r.points = 12;
  r.bytes = 4096;
  r.ms.load = 1.5;
  r.ms.match = 2.0;
  r.error = "cannot read 'x\"y'";
  EXPECT_EQ(sequence::toJsonLine(r),
            "{\"frame\":\"00/000001\",\"status\":\"failed\",\"points\":12,\"bytes\":4096,\"load_ms\":1.5,\"project_ms\":0.0,"
            "\"match_ms\":2.0,\"reproject_ms\":0.0,\"save_ms\":0.0,\"total_ms\":3.5,\"error\":\"cannot read "
            "'x\\\"y'\"}");
}

TEST(Manifest, AJsonLineReadsBackAsItsRecord) {
  sequence::FrameRecord r;
  r.frame = "00/0\"1\\x\n";
  r.status = "ok";
  r.points = 123456789;
  r.bytes = 9876543210;
  r.ms = {1.5, 2.34, 300.5, 4.0, 0.5};
  r.error = "a\tb\x02";
  const std::optional<sequence::FrameRecord> back = sequence::fromJsonLine(sequence::toJsonLine(r));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->frame, r.frame);
  EXPECT_EQ(back->status, "ok");
  EXPECT_EQ(back->points, r.points);
  EXPECT_EQ(back->bytes, r.bytes);
  EXPECT_EQ(back->ms.load, 1.5);
  EXPECT_EQ(back->ms.project, 2.3) << "as written: one decimal";
  EXPECT_EQ(back->ms.match, 300.5);
  EXPECT_EQ(back->ms.reproject, 4.0);
  EXPECT_EQ(back->ms.save, 0.5);
  EXPECT_EQ(back->error, r.error);
  for (const char* other : {"", "an older run's line", "{\"frame\":\"a\"}", "{\"frame\":\"a\",\"status\":\"ok\",\"points\":",
                            "[1, 2]"}) {
    EXPECT_FALSE(sequence::fromJsonLine(other).has_value()) << other;
  }
  const std::string line = sequence::toJsonLine(r);
  EXPECT_FALSE(sequence::fromJsonLine(line.substr(0, line.size() - 1)).has_value()) << "a line cut short";
}

TEST_F(FrameList, ASkippedFrameKeepsTheRecordOfTheRunThatMadeItsCloud) {
  sequence::FrameRecord made;
  made.frame = "000001";
  made.status = "ok";
  made.points = 5000;
  made.bytes = 80000;
  made.ms = {1, 2, 3, 4, 5};
  sequence::FrameRecord failed = made;
  failed.frame = "000002";
  failed.status = "failed";
  sequence::FrameRecord old = made;  // an older shard's record of frame 000001, overridden by the later manifest
  old.points = 1;
  write(root_ / "manifest.shard-0-of-2.jsonl", sequence::toJsonLine(old) + "\n");
  fs::last_write_time(root_ / "manifest.shard-0-of-2.jsonl", fs::file_time_type::clock::now() - std::chrono::hours(1));
  write(root_ / "manifest.jsonl", sequence::toJsonLine(made) + "\n" + sequence::toJsonLine(failed) + "\nnot json\n");
  write(root_ / "other.jsonl", sequence::toJsonLine(failed) + "\n");
  const std::map<std::string, sequence::FrameRecord> earlier = earlierFrameRecords(root_.string());
  ASSERT_EQ(earlier.size(), 1u) << "failed records carry nothing";
  EXPECT_EQ(earlier.at("000001").points, 5000u);

  const sequence::FrameRecord skipped = skippedFrameRecord("000001", 80000, earlier);
  EXPECT_EQ(skipped.status, "skipped");
  EXPECT_EQ(skipped.points, 5000u);
  EXPECT_EQ(skipped.bytes, 80000u);
  EXPECT_EQ(skipped.ms.total(), 15.0);
  // That skipped record, in the next run's manifest, carries the statistics on.
  write(root_ / "manifest.jsonl", sequence::toJsonLine(skipped) + "\n");
  EXPECT_EQ(earlierFrameRecords(root_.string()).at("000001").points, 5000u);

  const sequence::FrameRecord replaced = skippedFrameRecord("000001", 79999, earlier);
  EXPECT_EQ(replaced.points, 0u) << "a cloud of another size is not the one the record describes";
  EXPECT_EQ(replaced.bytes, 79999u);
  EXPECT_EQ(skippedFrameRecord("000003", 10, earlier).ms.total(), 0.0);
  EXPECT_TRUE(earlierFrameRecords((root_ / "missing").string()).empty());
}

TEST_F(FrameList, ManifestAppendsOneFlushedLinePerRecordAndStartsEmpty) {
  const std::string path = (root_ / "manifest.jsonl").string();
  write(path, "an older run's line\n");
  sequence::Manifest manifest(path);
  sequence::FrameRecord r;
  r.frame = "a";
  r.status = "ok";
  manifest.append(r);
  r.frame = "b";
  manifest.append(r);  // read while the manifest is open: each line is on disk already
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("{\"frame\":\"a\"", 0), 0u);
  EXPECT_EQ(lines[1].rfind("{\"frame\":\"b\"", 0), 0u);
  EXPECT_THROW(sequence::Manifest((root_ / "no" / "such" / "m.jsonl").string()), std::runtime_error);
}

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
