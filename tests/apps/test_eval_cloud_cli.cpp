// lidar_sgm_eval -cloud OUT -reference REF: one cloud against one reference in 3D, on two tiny
// PCD files written here (a grid and the same grid 0.25 m away), and its refusals.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/test_paths.hpp"
#include "common/run_command.hpp"

namespace lidar_sgm {
namespace {
namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult runTool(const std::string& arguments) {
  const std::string command = std::string(test::kEvalTool) + " " + arguments + " 2>&1";
  return test::runCommand(command);
}

/// An ASCII PCD of the points (x, y, z); "nan" is written as PCL writes it.
void writePcd(const fs::path& path, const std::vector<std::array<float, 3>>& points) {
  std::ofstream out(path);
  out << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << points.size()
      << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size() << "\nDATA ascii\n";
  for (const auto& p : points) out << p[0] << " " << p[1] << " " << p[2] << "\n";
}

/// A 4 x 3 grid of 1 m spacing at z = 5 + dz (ranges about 5 to 6.2 m, all in the 0-10 m band),
/// with `nans` NaN points after it.
std::vector<std::array<float, 3>> grid(float dz, int nans = 0) {
  std::vector<std::array<float, 3>> points;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) points.push_back({static_cast<float>(x), static_cast<float>(y), 5.0f + dz});
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < nans; ++i) points.push_back({nan, nan, nan});
  return points;
}

class EvalCloudCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lidar_sgm_eval_cloud_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    writePcd(dir_ / "cloud.pcd", grid(0.25f, 2));
    writePcd(dir_ / "reference.pcd", grid(0.0f));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const char* name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(EvalCloudCli, ScoresTheShiftedGridAndWritesJson) {
  const RunResult r = runTool("-cloud " + file("cloud.pcd") + " -reference " + file("reference.pcd") +
                              " -tau 0.2,0.25 -bands 0,10,20 -out " + file("out"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* text : {"Loading cloud", "[done", "14 points]", "tau 0.25 m", "0-10 m", "10-20 m",
                           "skipped (NaN or infinite): 2 cloud points"}) {
    EXPECT_NE(r.output.find(text), std::string::npos) << text << " in\n" << r.output;
  }
  std::ifstream jsonFile(dir_ / "out" / "cloud_distance.json");
  ASSERT_TRUE(jsonFile.good()) << r.output;
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  EXPECT_EQ(json.at("points").get<long>(), 12);
  EXPECT_EQ(json.at("reference_points").get<long>(), 12);
  EXPECT_EQ(json.at("skipped_points").get<long>(), 2);
  const nlohmann::json& taus = json.at("overall").at("taus");
  ASSERT_EQ(taus.size(), 2u);
  EXPECT_EQ(taus.at(0).at("f_score").get<double>(), 0.0);  // 0.25 m away: outside 0.2 m
  EXPECT_EQ(taus.at(1).at("precision").get<double>(), 1.0);
  EXPECT_EQ(taus.at(1).at("completeness").get<double>(), 1.0);
  EXPECT_EQ(json.at("overall").at("median_distance").get<double>(), 0.25);
  ASSERT_EQ(json.at("bands").size(), 2u);
  EXPECT_EQ(json.at("bands").at(0).at("points").get<long>(), 12);
  EXPECT_TRUE(json.at("bands").at(1).at("taus").at(1).at("precision").is_null());  // no point in 10-20 m
  EXPECT_EQ(json.at("band_edges").size(), 3u);
}

// One run per refusal (each starts the tool): the files and options the user gets wrong most;
// the library's own refusals are unit-tested (test_cloud_distance.cpp).
TEST_F(EvalCloudCli, BadInputsFailNamingTheProblem) {
  writePcd(dir_ / "empty.pcd", {});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  writePcd(dir_ / "nan.pcd", {{nan, nan, nan}, {nan, nan, nan}});
  std::ofstream(dir_ / "broken.pcd") << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4\n";
  const std::string cloud = " -cloud " + file("cloud.pcd");
  const std::string reference = " -reference " + file("reference.pcd");
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"-cloud " + file("missing.pcd") + reference, "missing.pcd"},
           {"-cloud " + file("broken.pcd") + reference, "broken.pcd"},
           {"-cloud " + file("empty.pcd") + reference, "empty.pcd' has no point"},
           {cloud + " -reference " + file("nan.pcd"), "the reference cloud has no finite point"},
           {cloud + reference + " -tau 0", "option -tau"},
           {cloud + reference + " -bands 0,20,10", "option -bands: cloud distance: band edges must increase"},
           {cloud, "needs -reference"},
           {cloud + reference + " -protocols P3", "option -protocols: not with -cloud"},
       }) {
    const RunResult r = runTool(args);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
}

}  // namespace
}  // namespace lidar_sgm
