// The cloud writers on a failing file system: a write cut short (here by a file size limit, which
// fails write() as a full disk does) replaces nothing and leaves nothing, in every format (the
// formats themselves: test_cloud_writers_match_pcl.cpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include <pcl/point_types.h>

#include "common/file_size_limit.hpp"
#include "lidar_sgm/io/cloud_io.hpp"

namespace lidar_sgm {
namespace io {
namespace {
namespace fs = std::filesystem;

struct Case {
  const char* name;  ///< the output's file name (its extension picks the file type)
  CloudFormat format;
};

const Case kCases[] = {{"binary.pcd", CloudFormat::Binary},
                       {"compressed.pcd", CloudFormat::Compressed},
                       {"ascii.pcd", CloudFormat::Ascii},
                       {"binary.ply", CloudFormat::Binary},
                       {"ascii.ply", CloudFormat::Ascii}};

class CloudWriterFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lidar_sgm_writer_faults_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Enough points that every format's file is far over the limit below, with varied values
    // (the compressed form must not shrink under it).
    for (int i = 0; i < 20000; ++i) {
      pcl::PointXYZRGB p;
      p.x = 0.001f * static_cast<float>(i * 7919 % 10007);
      p.y = -0.5f + 0.0001f * static_cast<float>(i);
      p.z = 5.0f + 0.01f * static_cast<float>(i % 977);
      p.r = static_cast<std::uint8_t>(i * 13);
      p.g = static_cast<std::uint8_t>(i * 29);
      p.b = static_cast<std::uint8_t>(i * 31);
      cloud_.push_back(p);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  std::string read(const std::string& path) const {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.insert(entry.path().filename().string());
    return names;
  }

  fs::path dir_;
  pcl::PointCloud<pcl::PointXYZRGB> cloud_;
};

TEST_F(CloudWriterFaults, AWriteCutShortReplacesNothingInAnyFormat) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    const std::string path = p(c.name);
    {
      std::ofstream earlier(path, std::ios::binary);
      earlier << "the earlier, complete cloud";
    }
    try {
      const test::FileSizeLimit limit(64 * 1024);
      writeCloud(path, cloud_, c.format);
      FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("cannot write '" + path + "': ", 0), 0u) << what;
      // The system's reason, or the read-back's for a writer that does not check its writes.
      EXPECT_TRUE(what.find("File too large") != std::string::npos || what.find("incomplete") != std::string::npos)
          << what;
    }
    EXPECT_EQ(read(path), "the earlier, complete cloud");
  }
  std::set<std::string> expected;
  for (const Case& c : kCases) expected.insert(c.name);
  EXPECT_EQ(entries(), expected);  // no temporary left
}

}  // namespace
}  // namespace io
}  // namespace lidar_sgm
