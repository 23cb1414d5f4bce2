// lidar_sgm_batch's pieces: frame discovery in each layout, list files and shards.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/frame_list_fixture.hpp"
#include "lidar_sgm/sequence/frame_list.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
namespace fs = std::filesystem;

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

}  // namespace
}  // namespace apps
}  // namespace lidar_sgm
