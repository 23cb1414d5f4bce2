// OutputTransaction: a run's outputs appear together or not at all, and what an interrupted run
// leaves is recognised and removed by the next.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "lidar_sgm/io/output_transaction.hpp"

namespace lidar_sgm {
namespace io {
namespace {
namespace fs = std::filesystem;

class OutputTransactionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_transaction_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  static void write(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
  }
  static std::string read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }

  fs::path dir_;
};

TEST_F(OutputTransactionTest, CommitPutsEveryOutputInPlace) {
  write(p("cloud.pcd"), "old cloud");
  {
    OutputTransaction outputs({p("cloud.pcd"), p("picture.png")});
    EXPECT_EQ(outputs.temporary(p("cloud.pcd")), p(".cloud.tmp" + std::to_string(::getpid()) + ".pcd"));
    write(outputs.temporary(p("cloud.pcd")), "new cloud");
    write(outputs.temporary(p("picture.png")), "new picture");
    EXPECT_EQ(read(p("cloud.pcd")), "old cloud") << "replaced before the commit";
    outputs.commit();
  }
  EXPECT_EQ(read(p("cloud.pcd")), "new cloud");
  EXPECT_EQ(read(p("picture.png")), "new picture");
  EXPECT_EQ(fileCount(), 2u);
}

TEST_F(OutputTransactionTest, AnOutputNotWrittenReplacesNothingAndLeavesNoTemporary) {
  write(p("cloud.pcd"), "old cloud");
  {
    OutputTransaction outputs({p("cloud.pcd"), p("picture.png")});
    write(outputs.temporary(p("cloud.pcd")), "new cloud");
    EXPECT_THROW(
        {
          try {
            outputs.commit();
          } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("picture.png"), std::string::npos) << e.what();
            throw;
          }
        },
        std::runtime_error);
  }
  EXPECT_EQ(read(p("cloud.pcd")), "old cloud");
  EXPECT_EQ(fileCount(), 1u) << "a temporary was left";
}

TEST_F(OutputTransactionTest, AnExceptionBeforeTheCommitLeavesNoTemporary) {
  try {
    OutputTransaction outputs({p("cloud.pcd")});
    write(outputs.temporary(p("cloud.pcd")), "half a clou");
    throw std::runtime_error("the computation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(fileCount(), 0u);
}

TEST_F(OutputTransactionTest, OutputsAreCheckedBeforeAnyWork) {
  fs::create_directories(p("folder.png"));
  auto expectRefused = [](const std::vector<std::string>& outputs, const std::string& message) {
    try {
      OutputTransaction transaction(outputs);
      ADD_FAILURE() << "accepted " << outputs.front();
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expectRefused({p("cloud.pcd"), p("folder.png")}, "cannot write '" + p("folder.png") + "': it is a folder");
  expectRefused({p("missing/picture.png")}, "the folder '" + p("missing") + "' does not exist");
  expectRefused({"/proc/lidar_sgm.png"}, "is not writable");
  EXPECT_EQ(fileCount(), 1u) << "a probe file was left";
  if (::geteuid() != 0) {  // root writes into a read-only folder: only a non-root run can check it
    fs::create_directories(p("read_only"));
    fs::permissions(p("read_only"), fs::perms::owner_read | fs::perms::owner_exec);
    expectRefused({p("read_only/cloud.pcd")}, "is not writable");
    fs::permissions(p("read_only"), fs::perms::owner_all);
  }
}

TEST_F(OutputTransactionTest, TemporariesOfDeadRunsAreRemovedAndALiveRunsAreKept) {
  // A process that has ended: its pid names no live process (the kernel does not reuse it while
  // we hold nothing; the wait below reaps it first).
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);
  const std::string dead = std::to_string(child);
  const std::string live = std::to_string(::getppid());
  write(p(".cloud.tmp" + dead + ".pcd"), "left by a killed run");
  write(p("..cloud.tmp" + dead + ".tmp" + dead + ".pcd"), "the writer's own, left by a killed run");
  write(p(".cloud.tmp" + live + ".pcd"), "a live run is writing this");
  write(p(".other.tmp" + dead + ".pcd"), "another output's");
  EXPECT_EQ(removeDeadRunTemporaries(p("cloud.pcd")), 2u);
  EXPECT_TRUE(fs::exists(p(".cloud.tmp" + live + ".pcd")));
  EXPECT_TRUE(fs::exists(p(".other.tmp" + dead + ".pcd")));
  EXPECT_FALSE(fs::exists(p(".cloud.tmp" + dead + ".pcd")));
  {
    OutputTransaction outputs({p("other.pcd")});  // the constructor cleans its outputs' too
  }
  EXPECT_FALSE(fs::exists(p(".other.tmp" + dead + ".pcd")));
}

TEST_F(OutputTransactionTest, SigtermRemovesTheTemporariesAndKillsTheRun) {
  write(p("cloud.pcd"), "old cloud");
  const pid_t child = ::fork();
  if (child == 0) {
    OutputTransaction outputs({p("cloud.pcd"), p("picture.png")});
    write(outputs.temporary(p("cloud.pcd")), "half a clou");
    ::kill(::getpid(), SIGTERM);
    ::_exit(3);  // not reached: the handler re-raises SIGTERM with its default action
  }
  ASSERT_GT(child, 0);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_EQ(read(p("cloud.pcd")), "old cloud");
  EXPECT_EQ(fileCount(), 1u) << "a temporary was left";
}

}  // namespace
}  // namespace io
}  // namespace lidar_sgm
