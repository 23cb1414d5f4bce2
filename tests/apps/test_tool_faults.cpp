// The tools on a failing file system and under concurrent runs, as users met them: a full disk
// (a small tmpfs) fails a frame or a run cleanly and never leaves a truncated cloud marked done,
// and a re-run recovers every cloud byte for byte; a cloud cut short by other means is redone;
// two runs on one output folder do not undo each other's work, while its shards run side by side.
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

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

/// The clouds under `dir` (file name -> bytes): its .pcd and .ply files.
std::map<std::string, std::string> clouds(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const std::string extension = e.path().extension().string();
    if (name[0] != '.' && (extension == ".pcd" || extension == ".ply")) files[name] = readText(e.path());
  }
  return files;
}

/// Hidden temporaries (".name.tmpPID[.ext]") under `dir`.
int temporaries(const fs::path& dir) {
  int count = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    count += name.rfind(".", 0) == 0 && name.find(".tmp") != std::string::npos ? 1 : 0;
  }
  return count;
}

/// A tmpfs of a given size mounted on a folder: a disk that fills. Mounting needs root (CI runs
/// as root); elsewhere available() is false and the tests that need it skip.
class SmallDisk {
 public:
  /// `flags`: mount(2)'s, e.g. MS_RDONLY for a read-only file system.
  SmallDisk(const fs::path& at, std::size_t bytes, unsigned long flags = 0) : at_(at) {
    fs::create_directories(at_);
    mounted_ = ::mount("tmpfs", at_.c_str(), "tmpfs", flags, options(bytes).c_str()) == 0;
    if (!mounted_) why_ = std::strerror(errno);
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(at_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

  bool available() const { return mounted_; }
  const std::string& why() const { return why_; }
  /// Gives the disk `bytes` in all, keeping its files (space freed, as a user would).
  void resize(std::size_t bytes) {
    ASSERT_EQ(::mount("tmpfs", at_.c_str(), "tmpfs", MS_REMOUNT, options(bytes).c_str()), 0) << std::strerror(errno);
  }

 private:
  static std::string options(std::size_t bytes) { return "size=" + std::to_string(bytes) + ",mode=0755"; }

  fs::path at_;
  bool mounted_ = false;
  std::string why_;
};

constexpr int kFrames = 4;

class ToolFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    synth_ = fs::temp_directory_path() / ("lidar_sgm_tool_faults_synth_" + std::to_string(getpid()));
    fs::remove_all(synth_);
    const RunResult r = shell(std::string(test::kSynthTool) + " -out " + synth_.string() + " -n " +
                              std::to_string(kFrames) + " -width 320 -height 96 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(synth_); }

  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("lidar_sgm_tool_faults_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
             "_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  /// The synthetic frames densified into `out` with `options`: the clouds a clean run makes.
  std::map<std::string, std::string> cleanRun(const fs::path& out, const std::string& options) {
    const RunResult r = batch("-input_dir " + synth_.string() + " -output_dir " + out.string() + " " + options);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return clouds(out);
  }

  static fs::path synth_;
  fs::path root_;
};

fs::path ToolFaults::synth_;

std::size_t totalBytes(const std::map<std::string, std::string>& files) {
  std::size_t total = 0;
  for (const auto& file : files) total += file.second.size();
  return total;
}

TEST_F(ToolFaults, AFullDiskFailsFramesCleanlyAndAReRunRecoversEveryCloudByteForByte) {
  for (const std::string options : {"-extension ply", "-format ascii", "-format compressed", "-extension ply -format ascii"}) {
    SCOPED_TRACE(options);
    const fs::path label = root_ / std::to_string(std::hash<std::string>()(options));
    const std::map<std::string, std::string> clean = cleanRun(label / "clean", options);
    ASSERT_EQ(clean.size(), static_cast<std::size_t>(kFrames));
    // Room for about half the clouds: some frames are written, the disk fills in another.
    SmallDisk disk(label / "disk", totalBytes(clean) / 2 + 64 * 1024);
    if (!disk.available()) GTEST_SKIP() << "cannot mount a small tmpfs (" << disk.why() << "): needs root";
    const fs::path out = label / "disk" / "out";
    const std::string line = "-input_dir " + synth_.string() + " -output_dir " + out.string() + " " + options;
    RunResult r = batch(line);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
    // Every cloud there is whole: exactly the clean run's; none is marked done without its cloud.
    const std::map<std::string, std::string> written = clouds(out);
    EXPECT_LT(written.size(), clean.size()) << r.output;
    for (const auto& [name, bytes] : written) EXPECT_TRUE(bytes == clean.at(name)) << name << " is not whole";
    for (const std::string& record : lines(out / "manifest.jsonl")) {
      const std::string frame = record.substr(10, 6);  // {"frame":"000001",...
      const bool ok = record.find("\"status\":\"ok\"") != std::string::npos;
      EXPECT_EQ(ok, written.count(frame + (options.find("ply") != std::string::npos ? ".ply" : ".pcd")) == 1)
          << record;
    }
    EXPECT_EQ(temporaries(out), 0);

    disk.resize(4 * totalBytes(clean) + 1024 * 1024);  // space freed
    r = batch(line);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(clouds(out) == clean) << r.output;
    EXPECT_EQ(temporaries(out), 0);
  }
}

TEST_F(ToolFaults, AFullDiskNeverReplacesLidarSgmDensifysOutput) {
  for (const std::string options : {"", "-format ascii", "-format compressed"}) {
    for (const std::string extension : {".pcd", ".ply"}) {
      if (extension == ".ply" && options == "-format compressed") continue;  // refused before any work
      SCOPED_TRACE(options + " " + extension);
      const fs::path label = root_ / std::to_string(std::hash<std::string>()(options + extension));
      SmallDisk disk(label, 64 * 1024);  // far less than a cloud
      if (!disk.available()) GTEST_SKIP() << "cannot mount a small tmpfs (" << disk.why() << "): needs root";
      const fs::path out = label / ("cloud" + extension);
      std::ofstream(out) << "the earlier cloud";
      const std::string s = synth_.string();
      const RunResult r =
          shell(std::string(test::kDensifyTool) + " " + s + "/velodyne/000000.bin " + out.string() + " -left " + s +
                "/image_2/000000.png -right " + s + "/image_3/000000.png -calib " + s + "/calib/000000.txt " +
                options + " 2>&1");
      EXPECT_EQ(r.exitCode, 1) << r.output;
      EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
      EXPECT_EQ(readText(out), "the earlier cloud");
      EXPECT_EQ(temporaries(label), 0);
    }
  }
}

TEST_F(ToolFaults, ACloudCutShortOrBrokenIsRedoneByTheNextRun) {
  const fs::path out = root_ / "out";
  const std::map<std::string, std::string> clean = cleanRun(out, "");
  ASSERT_EQ(clean.size(), static_cast<std::size_t>(kFrames));
  fs::resize_file(out / "000001.pcd", fs::file_size(out / "000001.pcd") - 100);  // as a full disk cut it
  std::ofstream(out / "000002.pcd", std::ios::trunc) << "not a cloud";           // broken by other means
  const RunResult r = batch("-input_dir " + synth_.string() + " -output_dir " + out.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2 ok, 2 skipped, 0 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("000001 ok"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(redone: the earlier cloud the manifest records "), std::string::npos) << r.output;
  EXPECT_TRUE(clouds(out) == clean);
  const std::vector<std::string> manifest = lines(out / "manifest.jsonl");
  ASSERT_EQ(manifest.size(), static_cast<std::size_t>(kFrames));
  EXPECT_NE(manifest[1].find("\"redone\":\"the manifest records "), std::string::npos) << manifest[1];
  EXPECT_NE(manifest[2].find("\"redone\":\""), std::string::npos) << manifest[2];
  EXPECT_EQ(manifest[0].find("redone"), std::string::npos) << manifest[0];

  // Without a manifest's record, the cloud itself is checked: header against body.
  fs::remove(out / "manifest.jsonl");
  fs::resize_file(out / "000003.pcd", fs::file_size(out / "000003.pcd") - 16);
  const RunResult again = batch("-input_dir " + synth_.string() + " -output_dir " + out.string());
  EXPECT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("1 ok, 3 skipped, 0 failed"), std::string::npos) << again.output;
  EXPECT_TRUE(clouds(out) == clean);
}

TEST_F(ToolFaults, ASecondRunOnTheSameFolderIsRefusedAndShardsRunSideBySide) {
  // Each first run is caught after its first frame and held there (SIGSTOP) while the others try:
  // whatever the machine's speed, it holds its lock then. 12 frames (links to one).
  constexpr int kLinks = 12;
  std::ofstream list(root_ / "frames.txt");
  for (int i = 0; i < kLinks; ++i) {
    const fs::path link = root_ / "scans" / ("s" + std::to_string(i) + ".bin");
    fs::create_directories(link.parent_path());
    fs::create_symlink(synth_ / "velodyne" / "000000.bin", link);
    list << link.string() << " " << synth_.string() << "/image_2/000000.png " << synth_.string()
         << "/image_3/000000.png " << synth_.string() << "/calib/000000.txt\n";
  }
  list.close();
  const fs::path out = root_ / "out";
  const std::string common = " -list " + (root_ / "frames.txt").string() + " -output_dir " + out.string() +
                             " -backend cpu_ref";
  // "until FILE has a line": the run has passed its start (lock, clean-up) and written a frame.
  const auto waitFor = [](const fs::path& manifest) {
    return "for i in $(seq 1 3000); do [ -s " + manifest.string() + " ] && break; sleep 0.01; done; ";
  };
  const std::string script = std::string(test::kBatchTool) + common + " > " + (root_ / "first.txt").string() +
                             " 2>&1 & first=$!; " + waitFor(out / "manifest.jsonl") + "kill -STOP $first; " +
                             test::kBatchTool + common + " > " + (root_ / "second.txt").string() +
                             " 2>&1; echo \"second=$? first=$first\"; kill -CONT $first; wait $first; echo \"first=$?\"";
  const RunResult r = shell("sh -c '" + script + "'");
  const std::string second = readText(root_ / "second.txt");
  const std::string firstPid = r.output.substr(r.output.find("first=") + 6, r.output.find('\n') - r.output.find("first=") - 6);
  EXPECT_NE(r.output.find("second=1 "), std::string::npos) << r.output << second;
  EXPECT_NE(second.find("Error: another lidar_sgm_batch run is writing '" + out.string() + "' (pid " + firstPid),
            std::string::npos)
      << second;
  EXPECT_NE(r.output.find("\nfirst=0"), std::string::npos) << r.output << readText(root_ / "first.txt");
  const std::vector<std::string> manifest = lines(out / "manifest.jsonl");
  EXPECT_EQ(manifest.size(), static_cast<std::size_t>(kLinks));
  for (const std::string& record : manifest) {
    EXPECT_EQ(record.rfind("{\"frame\":\"s", 0), 0u) << record;
    EXPECT_NE(record.find("\"status\":\"ok\""), std::string::npos) << record;
  }
  EXPECT_EQ(clouds(out).size(), static_cast<std::size_t>(kLinks));
  EXPECT_EQ(temporaries(out), 0);

  // The shards of one folder, side by side, and a whole run refused while they hold it.
  const fs::path sharded = root_ / "sharded";
  const std::string shards = " -list " + (root_ / "frames.txt").string() + " -output_dir " + sharded.string();
  const std::string both =
      std::string(test::kBatchTool) + shards + " -shard 0/2 -backend cpu_ref > /dev/null 2>&1 & a=$!; " +
      waitFor(sharded / "manifest.shard-0-of-2.jsonl") + "kill -STOP $a; " + test::kBatchTool + shards +
      " -shard 1/2 > /dev/null 2>&1; echo \"b=$?\"; " + test::kBatchTool + shards +
      " > /dev/null 2>&1; echo \"whole=$?\"; kill -CONT $a; wait $a; echo \"a=$?\"";
  const RunResult s = shell("sh -c '" + both + "'");
  EXPECT_NE(s.output.find("whole=1"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("a=0"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("b=0"), std::string::npos) << s.output;
  EXPECT_EQ(clouds(sharded).size(), static_cast<std::size_t>(kLinks));
}

}  // namespace
}  // namespace lidar_sgm

namespace lidar_sgm {
namespace {

TEST_F(ToolFaults, RefusalsNameTheSystemsCause) {
  const std::string s = synth_.string();
  const std::string scan = s + "/velodyne/000000.bin";
  const std::string pair = " -left " + s + "/image_2/000000.png -right " + s + "/image_3/000000.png";
  const std::string calib = " -calib " + s + "/calib/000000.txt";
  // A read-only file system: the folder check says so (errno of the failed create, not a later call's).
  {
    SmallDisk readOnly(root_ / "ro", 64 * 1024, MS_RDONLY);
    if (!readOnly.available()) GTEST_SKIP() << "cannot mount a tmpfs (" << readOnly.why() << "): needs root";
    const RunResult r = shell(std::string(test::kDensifyTool) + " " + scan + " " + (root_ / "ro" / "c.pcd").string() +
                              pair + calib + " 2>&1");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("is not writable (Read-only file system)"), std::string::npos) << r.output;
  }
  // A pipe or a device given as an input file is not "no such file".
  const fs::path fifo = root_ / "left.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  for (const std::string& inputs : {" -left " + fifo.string() + " -right " + s + "/image_3/000000.png" + calib,
                                    pair + " -calib /dev/zero"}) {
    SCOPED_TRACE(inputs);
    const RunResult r =
        shell(std::string(test::kDensifyTool) + " " + scan + " " + (root_ / "c.pcd").string() + inputs + " 2>&1");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("no such file"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace lidar_sgm
