// lidar_sgm_batch as a user runs it, on small sequences rendered by lidar_sgm_synth: its clouds
// are lidar_sgm_densify's byte for byte, whatever the layout, sharding and thread count; re-runs
// skip finished frames; a bad frame fails alone; a signal stops the run cleanly.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/test_data.hpp"
#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult shell(const std::string& command) {
  return test::runCommand(command);
}

RunResult batch(const std::string& arguments) { return shell(std::string(test::kBatchTool) + " " + arguments + " 2>&1"); }

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// Every regular file under `dir` (relative path -> bytes), manifests, the record of the cloud
/// options and the run's lock files left out.
std::map<std::string, std::string> clouds(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() || e.path().string().find("manifest") != std::string::npos ||
        e.path().filename() == "cloud_options.txt" || e.path().filename().string().rfind(".lidar_sgm_batch", 0) == 0) {
      continue;
    }
    files[fs::relative(e.path(), dir).string()] = readText(e.path());
  }
  return files;
}

/// Hidden temporary files (".name.tmpPID.ext") left under `dir`.
int temporaries(const fs::path& dir) {
  int count = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    count += name.rfind(".", 0) == 0 && name.find(".tmp") != std::string::npos ? 1 : 0;
  }
  return count;
}

/// The pid of a process that has ended (a child, reaped): what a killed run's temporaries carry.
long deadPid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return static_cast<long>(child);
}

constexpr int kFrames = 4;
const char* const kSize = "320x96";

class BatchTool : public ::testing::Test {
 protected:
  /// kFrames frames of 320x96 in the KITTI object layout, rendered once for the suite.
  static void SetUpTestSuite() {
    // Per process: ctest runs each test in its own process, several at once.
    synth_ = fs::temp_directory_path() / ("lidar_sgm_batch_synth_" + std::to_string(getpid()));
    fs::remove_all(synth_);
    const RunResult r = shell(std::string(test::kSynthTool) + " -out " + synth_.string() + " -n " +
                              std::to_string(kFrames) + " -width 320 -height 96 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(synth_); }

  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("lidar_sgm_batch_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  static std::string stem(int i) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d", i);
    return name;
  }

  /// The synthetic frames as a KITTI odometry sequence: velodyne/, image_2/, image_3/ and one
  /// calib.txt, the object calibration with its R0_rect (the identity here) folded into Tr.
  fs::path odometrySequence() {
    const fs::path seq = root_ / "seq" / "00";
    for (const char* folder : {"velodyne", "image_2", "image_3"}) {
      fs::create_directories(seq / folder);
      for (const fs::directory_entry& e : fs::directory_iterator(synth_ / folder)) {
        fs::copy_file(e.path(), seq / folder / e.path().filename());
      }
    }
    std::ofstream calib(seq / "calib.txt");
    for (const std::string& line : lines(synth_ / "calib" / "000000.txt")) {
      if (line.rfind("R0_rect:", 0) == 0) {
        std::istringstream numbers(line.substr(8));
        std::vector<double> r0;
        for (double v; numbers >> v;) r0.push_back(v);
        EXPECT_EQ(r0, (std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1})) << "the conversion assumes R0_rect = I";
        continue;
      }
      calib << (line.rfind("Tr_velo_to_cam:", 0) == 0 ? "Tr:" + line.substr(15) : line) << '\n';
    }
    return seq;
  }

  /// What a frame is given besides its scan and calibration.
  enum class Images { Pair, LeftOnly, None };

  /// lidar_sgm_densify's cloud of frame `i` of the object layout, run on its own.
  std::string densified(int i, Images images = Images::Pair) {
    const fs::path out = root_ / ("ref_" + stem(i) + ".pcd");
    const std::string s = synth_.string();
    std::string command = std::string(test::kDensifyTool) + " " + s + "/velodyne/" + stem(i) + ".bin " +
                          out.string() + " -calib " + s + "/calib/" + stem(i) + ".txt";
    if (images == Images::None) command += std::string(" -image_size ") + kSize;
    if (images != Images::None) command += " -left " + s + "/image_2/" + stem(i) + ".png";
    if (images == Images::Pair) command += " -right " + s + "/image_3/" + stem(i) + ".png";
    const RunResult r = shell(command + " 2>&1");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readText(out);
  }

  static fs::path synth_;
  fs::path root_;
};

fs::path BatchTool::synth_;

TEST_F(BatchTool, OdometrySequenceGivesLidarSgmDensifysCloudsByteForByte) {
  const fs::path seq = odometrySequence();
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + seq.string() + " -output_dir " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Summary: 4/4 frames: 4 ok, 0 skipped, 0 failed"), std::string::npos) << r.output;
  for (int i = 0; i < kFrames; ++i) {
    const std::string cloud = readText(out / (stem(i) + ".pcd"));
    ASSERT_FALSE(cloud.empty()) << stem(i);
    EXPECT_NE(cloud.find("FIELDS x y z rgb confidence"), std::string::npos);
    EXPECT_TRUE(cloud == densified(i)) << stem(i) << " differs from lidar_sgm_densify's";
  }
  const std::vector<std::string> manifest = lines(out / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_EQ(manifest[i].rfind("{\"frame\":\"" + stem(i) + "\",\"status\":\"ok\",\"points\":", 0), 0u) << manifest[i];
    EXPECT_EQ(manifest[i].find("\"points\":0,"), std::string::npos) << manifest[i];
  }
  EXPECT_EQ(temporaries(out), 0);
}

// lidar_sgm_synth -sequence writes the odometry layout itself (calib.txt with Tr:, poses.txt): the
// batch tool reads it as a sequence, with the clouds lidar_sgm_densify makes from the frame's
// object-format calibration.
TEST_F(BatchTool, SyntheticDriveIsReadAsAnOdometrySequence) {
  const fs::path drive = root_ / "drive";
  const RunResult rendered = shell(std::string(test::kSynthTool) +
                                   " -sequence 3 -seed 4 -width 320 -height 96 -out " + drive.string() + " 2>&1");
  ASSERT_EQ(rendered.exitCode, 0) << rendered.output;
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + drive.string() + " -output_dir " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Summary: 3/3 frames: 3 ok, 0 skipped, 0 failed"), std::string::npos) << r.output;
  for (int i = 0; i < 3; ++i) {
    const fs::path reference = root_ / ("ref_" + stem(i) + ".pcd");
    const std::string d = drive.string();
    const RunResult single = shell(std::string(test::kDensifyTool) + " " + d + "/velodyne/" + stem(i) + ".bin " +
                                   reference.string() + " -calib " + d + "/calib/" + stem(i) + ".txt -left " + d +
                                   "/image_2/" + stem(i) + ".png -right " + d + "/image_3/" + stem(i) + ".png 2>&1");
    ASSERT_EQ(single.exitCode, 0) << single.output;
    const std::string cloud = readText(out / (stem(i) + ".pcd"));
    ASSERT_FALSE(cloud.empty()) << stem(i);
    EXPECT_TRUE(cloud == readText(reference)) << stem(i) << " differs from lidar_sgm_densify's";
  }
}

TEST_F(BatchTool, ShardsAndThreadCountsGiveTheSameBytesAsOneProcess) {
  const fs::path one = root_ / "one";
  const fs::path sharded = root_ / "sharded";
  const std::string input = "-input_dir " + synth_.string();  // the object layout
  ASSERT_EQ(batch(input + " -output_dir " + one.string() + " -jobs 1 -threads 1").exitCode, 0);
  for (const char* shard : {"0/2", "1/2"}) {
    const RunResult r = batch(input + " -output_dir " + sharded.string() + " -jobs 2 -threads 2 -shard " + shard);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 frame(s) (shard " + std::string(shard) + " of 4)"), std::string::npos) << r.output;
  }
  const std::map<std::string, std::string> a = clouds(one);
  EXPECT_EQ(a.size(), static_cast<std::size_t>(kFrames));
  EXPECT_TRUE(a == clouds(sharded)) << "the sharded run's clouds differ";
  // Frames densified three at a time: the same clouds, and the manifest still in frame order.
  const fs::path jobs = root_ / "jobs";
  const RunResult three = batch(input + " -output_dir " + jobs.string() + " -jobs 3");
  ASSERT_EQ(three.exitCode, 0) << three.output;
  EXPECT_NE(three.output.find("3 job(s) x 1 matcher thread(s)"), std::string::npos) << three.output;
  EXPECT_TRUE(a == clouds(jobs)) << "the clouds of -jobs 3 differ";
  const std::vector<std::string> inOrder = lines(jobs / "manifest.jsonl");
  ASSERT_EQ(inOrder.size(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) EXPECT_EQ(inOrder[i].rfind("{\"frame\":\"" + stem(i) + "\"", 0), 0u) << inOrder[i];
  // Each frame is in exactly one shard's manifest: frame i in shard i % 2.
  for (int k = 0; k < 2; ++k) {
    const std::vector<std::string> m = lines(sharded / ("manifest.shard-" + std::to_string(k) + "-of-2.jsonl"));
    ASSERT_EQ(m.size(), 2u);
    EXPECT_EQ(m[0].rfind("{\"frame\":\"" + stem(k) + "\"", 0), 0u) << m[0];
    EXPECT_EQ(m[1].rfind("{\"frame\":\"" + stem(k + 2) + "\"", 0), 0u) << m[1];
  }
}

/// A manifest line's statistics: the line without its status and total_ms (the sum, which a
/// record read back from its rounded parts may print a tenth apart).
std::string statisticsOf(std::string line) {
  for (const char* status : {"\"status\":\"ok\",", "\"status\":\"skipped\","}) {
    const std::size_t at = line.find(status);
    if (at != std::string::npos) line.erase(at, std::string(status).size());
  }
  const std::size_t total = line.find(",\"total_ms\":");
  if (total != std::string::npos) line.erase(total, line.find(',', total + 1) - total);
  return line;
}

TEST_F(BatchTool, ReRunSkipsCompleteFramesAndOverwriteRedoesThem) {
  const fs::path out = root_ / "out";
  const std::string line = "-input_dir " + synth_.string() + " -output_dir " + out.string();
  RunResult r = batch(line);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // The layout and the frame count come first, before any frame.
  const std::size_t input = r.output.find("Input " + synth_.string() + ": KITTI object layout, 4 frame(s)\n");
  EXPECT_NE(input, std::string::npos) << r.output;
  EXPECT_LT(input, r.output.find("000000 ok")) << r.output;
  const std::map<std::string, std::string> first = clouds(out);
  const fs::file_time_type written = fs::last_write_time(out / "000002.pcd");
  const std::vector<std::string> made = lines(out / "manifest.jsonl");
  ASSERT_EQ(made.size(), static_cast<std::size_t>(kFrames));

  // Skipped frames keep the statistics of the run that made their clouds (points, bytes, timings).
  r = batch(line);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("0 ok, 4 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(out / "000002.pcd"), written);
  std::vector<std::string> manifest = lines(out / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    const std::string& m = manifest[static_cast<std::size_t>(i)];
    EXPECT_NE(m.find("\"status\":\"skipped\""), std::string::npos) << m;
    EXPECT_EQ(m.find("\"points\":0,"), std::string::npos) << m;
    EXPECT_EQ(statisticsOf(m), statisticsOf(made[static_cast<std::size_t>(i)]));
  }

  fs::remove(out / "000001.pcd");
  r = batch(line);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("000001 ok"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 ok, 3 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_TRUE(clouds(out) == first);
  manifest = lines(out / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  EXPECT_NE(manifest[1].find("\"status\":\"ok\""), std::string::npos) << manifest[1];
  for (int i : {0, 2, 3}) {
    EXPECT_EQ(statisticsOf(manifest[static_cast<std::size_t>(i)]), statisticsOf(made[static_cast<std::size_t>(i)]))
        << "carried over twice";
  }

  r = batch(line + " -overwrite");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("4 ok, 0 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_TRUE(clouds(out) == first);
}

TEST_F(BatchTool, ABadFrameIsReportedAndSkippedWhileTheOthersGoOn) {
  const fs::path seq = odometrySequence();
  std::ofstream(seq / "velodyne" / "000001.bin", std::ios::binary | std::ios::trunc) << "truncated";
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + seq.string() + " -output_dir " + out.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("Error: frame 000001: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 ok, 0 skipped, 1 failed"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "000001.pcd"));
  for (int i : {0, 2, 3}) EXPECT_TRUE(fs::exists(out / (stem(i) + ".pcd"))) << i;
  const std::vector<std::string> manifest = lines(out / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  EXPECT_NE(manifest[1].find("\"status\":\"failed\""), std::string::npos) << manifest[1];
  EXPECT_NE(manifest[1].find("000001.bin"), std::string::npos) << "the error names the file: " << manifest[1];
  EXPECT_EQ(temporaries(out), 0);
}

TEST_F(BatchTool, AMissingScanIsAFailedFrameNamingTheFileNotAGapInTheSequence) {
  const fs::path seq = odometrySequence();
  fs::remove(seq / "velodyne" / "000002.bin");  // its images are still there
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + seq.string() + " -output_dir " + out.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(std::to_string(kFrames) + " frame(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Error: frame 000002: cannot read cloud '" + (seq / "velodyne" / "000002.bin").string() +
                          "': no such file"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("3 ok, 0 skipped, 1 failed"), std::string::npos) << r.output;
}

TEST_F(BatchTool, AFrameWhoseImagesAreNotTheSequencesSizeIsRefused) {
  const fs::path seq = odometrySequence();
  // Frame 1's pair at half size: KITTI's calib.txt has no size, the sequence's first image gives it.
  for (const char* folder : {"image_2", "image_3"}) {
    const fs::path image = seq / folder / "000001.png";
    cv::Mat half;
    cv::resize(cv::imread(image.string(), cv::IMREAD_UNCHANGED), half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    ASSERT_TRUE(cv::imwrite(image.string(), half));
  }
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + seq.string() + " -output_dir " + out.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("Error: frame 000001: the left image '" + (seq / "image_2" / "000001.png").string() +
                          "' is 160x48 but the calibration '" + (seq / "calib.txt").string() +
                          "' is the sequence's, whose images are 320x96"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("3 ok, 0 skipped, 1 failed"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "000001.pcd"));
}

TEST_F(BatchTool, ListFileFramesWithoutImagesRunLidarOnlyAsLidarSgmDensifyDoes) {
  const std::string s = synth_.string();
  std::ofstream(root_ / "frames.txt") << "# scan left right calib\n"
                                      << s << "/velodyne/000000.bin " << s << "/image_2/000000.png " << s
                                      << "/image_3/000000.png " << s << "/calib/000000.txt\n"
                                      << s << "/velodyne/000001.bin - - " << s << "/calib/000001.txt\n";
  const fs::path out = root_ / "out";
  const RunResult r = batch("-list " + (root_ / "frames.txt").string() + " -output_dir " + out.string() +
                            " -image_size " + kSize);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(readText(out / "000000.pcd") == densified(0));
  const std::string lidarOnly = readText(out / "000001.pcd");
  EXPECT_NE(lidarOnly.find("FIELDS x y z confidence"), std::string::npos);
  EXPECT_TRUE(lidarOnly == densified(1, Images::None)) << "the LiDAR-only frame differs from lidar_sgm_densify's";
}

TEST_F(BatchTool, EveryFrameGetsItsOwnImagesInEveryOrderAndJobCount) {
  // A frame with a left image but no right one is LiDAR-only colored from its left image, as
  // lidar_sgm_densify -left makes it, also when the worker densified a pair before it.
  const std::string s = synth_.string();
  const std::vector<Images> kinds{Images::Pair, Images::LeftOnly, Images::None, Images::Pair};
  std::vector<std::string> expected;
  for (int i = 0; i < kFrames; ++i) expected.push_back(densified(i, kinds[static_cast<std::size_t>(i)]));
  std::vector<int> order{0, 1, 2, 3};
  int runs = 0;
  do {
    std::ofstream list(root_ / "frames.txt");
    for (const int i : order) {
      const Images kind = kinds[static_cast<std::size_t>(i)];
      list << s << "/velodyne/" << stem(i) << ".bin "
           << (kind == Images::None ? std::string("-") : s + "/image_2/" + stem(i) + ".png") << ' '
           << (kind == Images::Pair ? s + "/image_3/" + stem(i) + ".png" : std::string("-")) << ' ' << s << "/calib/"
           << stem(i) << ".txt\n";
    }
    list.close();
    for (const char* jobs : {"1", "2"}) {
      const fs::path out = root_ / ("out_" + std::to_string(runs));
      const RunResult r = batch("-list " + (root_ / "frames.txt").string() + " -output_dir " + out.string() +
                                " -image_size " + kSize + " -jobs " + jobs);
      ASSERT_EQ(r.exitCode, 0) << r.output;
      for (int i = 0; i < kFrames; ++i) {
        EXPECT_TRUE(readText(out / (stem(i) + ".pcd")) == expected[static_cast<std::size_t>(i)])
            << "frame " << i << " of the order " << order[0] << order[1] << order[2] << order[3] << ", -jobs " << jobs
            << " differs from lidar_sgm_densify's run of that frame alone";
      }
      fs::remove_all(out);
      ++runs;
    }
  } while (std::next_permutation(order.begin() + 1, order.end()) && runs < 12);
  EXPECT_EQ(runs, 12);
}

TEST_F(BatchTool, KittiRawDriveReadsTheDateFoldersCalibrationAsLidarSgmDensifyDoes) {
  if (!test::haveSharedData("kitti_raw_calib_2011_09_26")) GTEST_SKIP() << "no KITTI raw calibration";
  // A drive with the date's real calibration files above it and a scan without images.
  const fs::path date = root_ / "2011_09_26";
  const fs::path drive = date / "2011_09_26_drive_0001_sync";
  fs::create_directories(drive / "velodyne_points" / "data");
  for (const char* file : {"calib_cam_to_cam.txt", "calib_velo_to_cam.txt"}) {
    fs::copy_file(fs::path(test::sharedDataRoot()) / "kitti_raw_calib_2011_09_26" / file, date / file);
  }
  const fs::path scan = drive / "velodyne_points" / "data" / "0000000000.bin";
  fs::copy_file(synth_ / "velodyne" / "000000.bin", scan);
  const fs::path out = root_ / "out";
  const RunResult r = batch("-input_dir " + drive.string() + " -output_dir " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const fs::path reference = root_ / "ref.pcd";
  const RunResult d = shell(std::string(test::kDensifyTool) + " " + scan.string() + " " + reference.string() +
                            " -calib " + date.string() + " 2>&1");
  ASSERT_EQ(d.exitCode, 0) << d.output;
  EXPECT_TRUE(readText(out / "0000000000.pcd") == readText(reference));
}

TEST_F(BatchTool, VoxelShrinksEveryFrameAsLidarSgmDensifyDoesAndTheSizesAreReported) {
  const fs::path full = root_ / "full";
  const fs::path voxel = root_ / "voxel";
  const std::string input = "-input_dir " + synth_.string();
  ASSERT_EQ(batch(input + " -output_dir " + full.string()).exitCode, 0);
  const RunResult r = batch(input + " -output_dir " + voxel.string() + " -voxel 0.25");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("MB written; load "), std::string::npos) << r.output;
  const std::vector<std::string> manifest = lines(voxel / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    const fs::path cloud = voxel / (stem(i) + ".pcd");
    EXPECT_LT(fs::file_size(cloud) * 2, fs::file_size(full / (stem(i) + ".pcd"))) << stem(i);
    EXPECT_NE(manifest[i].find("\"bytes\":" + std::to_string(fs::file_size(cloud)) + ","), std::string::npos)
        << manifest[i];
  }
  // The same down-sampling as the single-frame tool, byte for byte.
  const fs::path reference = root_ / "ref.pcd";
  const std::string s = synth_.string();
  const RunResult d = shell(std::string(test::kDensifyTool) + " " + s + "/velodyne/000001.bin " +
                            reference.string() + " -calib " + s + "/calib/000001.txt -left " + s +
                            "/image_2/000001.png -right " + s + "/image_3/000001.png -voxel 0.25 2>&1");
  ASSERT_EQ(d.exitCode, 0) << d.output;
  EXPECT_TRUE(readText(reference) == readText(voxel / "000001.pcd"));
  // A skipped frame reports its existing file's size.
  const RunResult again = batch(input + " -output_dir " + voxel.string() + " -voxel 0.25");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(lines(voxel / "manifest.jsonl")[0].find("\"bytes\":" + std::to_string(fs::file_size(voxel / "000000.pcd"))),
            std::string::npos);
}

TEST_F(BatchTool, ARunWithOtherCloudOptionsIsRefusedInsteadOfMixingTwoMethods) {
  const fs::path out = root_ / "out";
  const std::string input = "-input_dir " + synth_.string() + " -output_dir " + out.string();
  ASSERT_EQ(batch(input + " -alpha 0.70 -threads 1").exitCode, 0);
  // The same cloud options (numbers written otherwise, other thread and job counts): skipped.
  const RunResult same = batch(input + " -alpha 0.7 -threads 2 -jobs 1");
  ASSERT_EQ(same.exitCode, 0) << same.output;
  EXPECT_NE(same.output.find("0 ok, 4 skipped"), std::string::npos) << same.output;
  const std::string before = clouds(out).begin()->second;
  // Other options: refused before any frame, naming both; nothing changed.
  const RunResult other = batch(input + " -alpha 0.5");
  EXPECT_EQ(other.exitCode, 1) << other.output;
  EXPECT_NE(other.output.find("were made with other options (-extension pcd -alpha 0.7) than this run's "
                              "(-extension pcd -alpha 0.5)"),
            std::string::npos)
      << other.output;
  EXPECT_TRUE(clouds(out).begin()->second == before);
  // -overwrite redoes every frame with the new options, and records them.
  const RunResult redo = batch(input + " -alpha 0.5 -overwrite");
  ASSERT_EQ(redo.exitCode, 0) << redo.output;
  EXPECT_FALSE(clouds(out).begin()->second == before);
  EXPECT_EQ(readText(out / "cloud_options.txt"), "-extension pcd\n-alpha 0.5\n");
}

TEST_F(BatchTool, TemporariesOfAKilledRunAreRemovedOnlyForThisShardsFrames) {
  const fs::path out = root_ / "out";
  fs::create_directories(out);
  // As kill -9 leaves them: a hidden temporary per frame, from a process that has ended; and one
  // of a live process (this test's), which is never touched.
  const std::string dead = ".tmp" + std::to_string(deadPid()) + ".pcd";
  for (int i = 0; i < kFrames; ++i) std::ofstream(out / ("." + stem(i) + dead)) << "half a cloud";
  const std::string live = "." + stem(2) + ".tmp" + std::to_string(getpid()) + ".pcd";
  std::ofstream(out / live) << "a live writer's";
  std::ofstream(out / ".notes.tmp1.pcd") << "not a frame of this sequence";
  const RunResult r = batch("-input_dir " + synth_.string() + " -output_dir " + out.string() + " -shard 0/2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("(removed 2 temporary file(s) an interrupted run left)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / ("." + stem(0) + dead)));
  EXPECT_TRUE(fs::exists(out / ("." + stem(1) + dead))) << "shard 1's frame: not this process's";
  EXPECT_FALSE(fs::exists(out / ("." + stem(2) + dead)));
  EXPECT_TRUE(fs::exists(out / ("." + stem(3) + dead)));
  EXPECT_TRUE(fs::exists(out / live)) << "its writer is alive";
  EXPECT_TRUE(fs::exists(out / ".notes.tmp1.pcd"));
}

TEST_F(BatchTool, ProgressLineEveryNFramesOnStderr) {
  const RunResult r = shell(std::string(test::kBatchTool) + " -input_dir " + synth_.string() + " -output_dir " +
                            (root_ / "out").string() + " -progress 2 2>&1 >/dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Progress: 2/4 frames (50 %), "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Progress: 4/4 frames (100 %), "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" frames/s, ETA "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Progress: 1/4"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Progress: 3/4"), std::string::npos) << r.output;
}

TEST_F(BatchTool, OnATerminalOneProgressLineIsRedrawnInPlace) {
  if (shell("command -v script >/dev/null 2>&1").exitCode != 0) GTEST_SKIP() << "no 'script' to give the tool a terminal";
  // util-linux's script runs the tool on a pseudo-terminal: stderr is a terminal there.
  const std::string command = std::string(test::kBatchTool) + " -input_dir " + synth_.string() + " -output_dir " +
                              (root_ / "out").string() + " -progress 2";
  const RunResult r = shell("script -qfec '" + command + "' /dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // "\r\033[K" returns to the line's start and clears it; the last state stays on its own line.
  EXPECT_NE(r.output.find("\r\033[KProgress: 4/4 frames (100 %), "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("\nProgress: "), std::string::npos) << "no plain log lines on a terminal";
  EXPECT_NE(r.output.find("Summary: 4/4 frames"), std::string::npos) << r.output;
}

TEST_F(BatchTool, ASignalFinishesTheCurrentFrameThenStopsLeavingNoPartialFile) {
  // 40 frames (links to one scan), slowed by the reference backend, so the signal comes mid-run.
  constexpr int kLinks = 40;
  std::ofstream list(root_ / "frames.txt");
  for (int i = 0; i < kLinks; ++i) {
    const fs::path link = root_ / "scans" / ("s" + std::to_string(i) + ".bin");
    fs::create_directories(link.parent_path());
    fs::create_symlink(synth_ / "velodyne" / "000000.bin", link);
    list << link.string() << " " << synth_.string() << "/image_2/000000.png " << synth_.string()
         << "/image_3/000000.png " << synth_.string() << "/calib/000000.txt\n";
  }
  list.close();
  for (const auto& [name, number] : std::vector<std::pair<std::string, int>>{{"INT", 2}, {"TERM", 15}}) {
    const fs::path out = root_ / ("out_" + name);
    const std::string script =
        std::string(test::kBatchTool) + " -list " + (root_ / "frames.txt").string() + " -output_dir " +
        out.string() + " -backend cpu_ref >" + (root_ / "log.txt").string() + " 2>&1 & pid=$!; " +
        "for i in $(seq 1 500); do [ -s " + (out / "manifest.jsonl").string() + " ] && break; sleep 0.01; done; " +
        "kill -" + name + " $pid; wait $pid; echo \"rc=$?\"";
    const RunResult r = shell("sh -c '" + script + "'");
    const std::string log = readText(root_ / "log.txt");
    EXPECT_NE(r.output.find("rc=" + std::to_string(128 + number)), std::string::npos) << r.output << log;
    EXPECT_NE(log.find("(stopped by signal " + std::to_string(number) + ")"), std::string::npos) << log;
    const std::vector<std::string> manifest = lines(out / "manifest.jsonl");
    EXPECT_GE(manifest.size(), 1u);
    EXPECT_LT(manifest.size(), static_cast<std::size_t>(kLinks)) << "the run was not stopped";
    EXPECT_EQ(clouds(out).size(), manifest.size()) << "every finished frame, and only those, has its cloud";
    EXPECT_EQ(temporaries(out), 0);
  }
}

}  // namespace
}  // namespace lidar_sgm
