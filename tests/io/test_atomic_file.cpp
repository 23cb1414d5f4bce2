// io::AtomicFile: an output appears whole or not at all; a failed write (here a file size limit,
// which fails a write() as a full disk does) replaces nothing and leaves nothing.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include "common/file_size_limit.hpp"
#include "lidar_sgm/io/atomic_file.hpp"

namespace lidar_sgm {
namespace io {
namespace {
namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lidar_sgm_atomic_file_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  std::string read(const std::string& name) const {
    std::ifstream in(p(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.insert(entry.path().filename().string());
    return names;
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, WriteReplacesTheFileAndLeavesOnlyIt) {
  writeFileAtomically(p("report.md"), std::string("old"));
  writeFileAtomically(p("report.md"), std::string("| a | b |\n"));
  EXPECT_EQ(read("report.md"), "| a | b |\n");
  EXPECT_EQ(entries(), std::set<std::string>{"report.md"});
}

TEST_F(AtomicFileTest, AMissingFolderIsNamedAndNothingIsLeft) {
  const std::string path = p("missing/report.json");
  try {
    writeFileAtomically(path, std::string("{}"));
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '" + path + "'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, AFailedWriteReplacesNothingLeavesNothingAndSaysWhy) {
  writeFileAtomically(p("cloud.pcd"), std::string("the earlier, complete file"));
  const std::string big(100000, 'x');
  try {
    const test::FileSizeLimit limit(4096);
    writeFileAtomically(p("cloud.pcd"), big);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '" + p("cloud.pcd") + "': File too large"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read("cloud.pcd"), "the earlier, complete file");
  EXPECT_EQ(entries(), std::set<std::string>{"cloud.pcd"});
}

TEST_F(AtomicFileTest, AFileNotCommittedIsRemoved) {
  {
    AtomicFile file(p("cloud.pcd"));
    file.write(std::string("half"));
    EXPECT_TRUE(fs::exists(file.temporaryPath()));
  }
  EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, TwoWritersOfOnePathInOneProcessDoNotShareATemporary) {
  AtomicFile first(p("cloud.pcd"));
  AtomicFile second(p("cloud.pcd"));
  EXPECT_NE(first.temporaryPath(), second.temporaryPath());
  first.write(std::string("first"));
  second.write(std::string("second"));
  first.commit();
  second.commit();
  EXPECT_EQ(read("cloud.pcd"), "second");
  EXPECT_EQ(entries(), std::set<std::string>{"cloud.pcd"});
}

TEST(TemporaryName, IsReadBackFromTheNameTheWritersGive) {
  const std::string temporary = temporaryPathFor("/out/000001.pcd", 4242);
  EXPECT_EQ(temporary, "/out/.000001.tmp4242.pcd");
  const auto name = parseTemporaryName(fs::path(temporary).filename().string());
  ASSERT_TRUE(name);
  EXPECT_EQ(name->output, "000001.pcd");
  EXPECT_EQ(name->pid, 4242);

  const auto second = parseTemporaryName(".map.v2.tmp17-3.pcd");  // a taken name's successor, dots in the stem
  ASSERT_TRUE(second);
  EXPECT_EQ(second->output, "map.v2.pcd");
  EXPECT_EQ(second->pid, 17);

  const auto nested = parseTemporaryName("..cloud.tmp5.tmp6.ply");  // a writer's temporary of a temporary
  ASSERT_TRUE(nested);
  EXPECT_EQ(nested->output, ".cloud.tmp5.ply");
  EXPECT_EQ(nested->pid, 6);

  const auto bare = parseTemporaryName(".options.tmp9");  // no extension
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->output, "options");

  for (const char* other : {"cloud.pcd", ".cloud.pcd", ".cloud.tmpx.pcd", ".cloud.tmp.pcd", "cloud.tmp5.pcd"}) {
    EXPECT_FALSE(parseTemporaryName(other)) << other;
  }
}

TEST(ProcessAlive, KnowsThisProcessAndAReapedChild) {
  EXPECT_TRUE(processAlive(static_cast<long>(::getpid())));
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_FALSE(processAlive(static_cast<long>(child)));
  EXPECT_FALSE(processAlive(0));
}

}  // namespace
}  // namespace io
}  // namespace lidar_sgm
