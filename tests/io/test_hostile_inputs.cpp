// The readers' regression corpus (tests/data/hostile/, README there): files that crashed,
// hung or fooled the readers, each now refused with a std::runtime_error naming the file and
// the problem, through the same entry point the tools use (io::readCloud).

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "common/test_paths.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

struct HostileFile {
  const char* name;
  const char* fragment;  ///< the problem the message must name
};

std::ostream& operator<<(std::ostream& out, const HostileFile& file) { return out << file.name; }

class HostileCloud : public ::testing::TestWithParam<HostileFile> {};

TEST_P(HostileCloud, IsRefusedWithAMessageNamingFileAndProblem) {
  const std::string path = (fs::path(test::kHostileDataDir) / GetParam().name).string();
  ASSERT_TRUE(fs::exists(path)) << path;
  const auto start = std::chrono::steady_clock::now();
  try {
    io::readCloud(path);
    ADD_FAILURE() << "no exception for " << path;
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().fragment), std::string::npos) << message;
  }
  // Each was refused from its header: none may take the seconds a parse of gigabytes would.
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, HostileCloud,
    ::testing::Values(HostileFile{"pcd_size_again_after_type.pcd", "'SIZE' appears again"},
                      HostileFile{"pcd_compressed_sizes_zero.pcd", "declares 0 uncompressed bytes"},
                      HostileFile{"pcd_compressed_size_huge.pcd", "declares 4294967280 uncompressed bytes"},
                      HostileFile{"pcd_compressed_lying_expansion.pcd", "cannot hold"},
                      HostileFile{"pcd_points_250M.pcd", "limit of 50000000 points"},
                      HostileFile{"pcd_points_over_data.pcd", "truncated"},
                      HostileFile{"pcd_ascii_not_a_number.pcd", "line 11: value 'abc' of field 'x' is not a float32"},
                      HostileFile{"pcd_points_not_width_height.pcd", "is not WIDTH x HEIGHT"},
                      HostileFile{"pcd_bad_type_size.pcd", "TYPE 'F' with SIZE 3"},
                      HostileFile{"ply_vertex_count_4294967297.ply", "limit of 50000000 points"},
                      HostileFile{"ply_list_in_vertex.ply", "list property 'idx' in element vertex"},
                      HostileFile{"ply_list_count_ffffffff.ply", "truncated"},
                      HostileFile{"ply_leading_space_cut.ply", "truncated"},
                      HostileFile{"ply_vertex_negative.ply", "with a count of 0 or more"},
                      HostileFile{"ply_element_without_properties.ply", "declares 18446744073709551615 entries"},
                      HostileFile{"ply_ascii_not_a_number.ply", "line 9: value 'abc' of property 'x' is not a float32"}),
    [](const ::testing::TestParamInfo<HostileFile>& param) {
      std::string name = fs::path(param.param.name).stem().string();
      for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

// Images: every reader the tools use goes through the same signature check before OpenCV.
TEST(HostileImage, DicomMagicBehindAPngLookalikeIsRefusedBeforeOpenCv) {
  const std::string path = (fs::path(test::kHostileDataDir) / "png_dicom_magic.png").string();
  ASSERT_TRUE(fs::exists(path)) << path;
  const std::string expected = "cannot read image '" + path + "': not a PNG, JPEG or PGM/PPM file";
  for (const auto& read : {+[](const std::string& p) { io::readImage(p); },
                           +[](const std::string& p) { io::readKittiDisparity(p); },
                           +[](const std::string& p) { io::readKittiDepthAsDisparity(p, 389.0); }}) {
    try {
      read(path);
      ADD_FAILURE() << "no exception for " << path;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
