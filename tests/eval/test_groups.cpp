// Which frames form which table: the selection's protocols and P3 sets, in the documented order,
// each with its methods; a name that would select nothing is refused.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "common/test_data.hpp"
#include "lidar_sgm/eval/group_run.hpp"
#include "lidar_sgm/eval/groups.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

GroupSelection tinySelection() {
  GroupSelection s;
  s.dataRoot = test::sharedDataRoot();
  s.synthFrames = 1;
  s.synthWidth = 160;
  s.synthHeight = 64;
  return s;
}

TEST(Groups, P3SetsInOrderWithTheThirdCameraOnlyInClear64) {
  GroupSelection s = tinySelection();
  s.protocols = {"P3"};
  s.p3Sets = {"clear128", "clear64", "rain64"};  // the order is the documented one, not this
  const std::vector<FrameGroup> groups = loadGroups(s);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].name, "P3 clear 64 beams");
  EXPECT_EQ(groups[1].name, "P3 rain 64 beams");
  EXPECT_EQ(groups[2].name, "P3 clear 128 beams");
  const std::size_t base = baseMethods().size();
  EXPECT_EQ(groups[0].methods.size(), base + 2) << "Triple-SGM without and with LiDAR";
  EXPECT_EQ(groups[1].methods.size(), base);
  EXPECT_EQ(groups[2].methods.size(), base);
  for (const FrameGroup& g : groups) {
    ASSERT_EQ(g.frames.size(), 1u) << g.name;
    EXPECT_EQ(g.frames[0].left.cols, 160) << g.name;
  }
  EXPECT_NE(groups[0].description.find("third camera"), std::string::npos) << groups[0].description;
  EXPECT_NE(groups[1].description.find("rain"), std::string::npos) << groups[1].description;
  EXPECT_NE(groups[2].description.find("128-beam"), std::string::npos) << groups[2].description;

  s.p3Sets = {"rain64"};
  ASSERT_EQ(loadGroups(s).size(), 1u);
}

TEST(Groups, RealDataGroupsComeFirstAndAbsentDataGivesNone) {
  GroupSelection s = tinySelection();
  s.protocols = {"P1", "P2", "P3"};
  s.p3Sets = {"clear64"};
  const std::vector<FrameGroup> groups = loadGroups(s);
  ASSERT_FALSE(groups.empty());
  EXPECT_EQ(groups.back().name, "P3 clear 64 beams");
  for (std::size_t i = 0; i + 1 < groups.size(); ++i) {
    EXPECT_TRUE(groups[i].name.rfind("P1 ", 0) == 0 || groups[i].name == "P2 real LiDAR") << groups[i].name;
    EXPECT_FALSE(groups[i].frames.empty()) << groups[i].name;
    if (i > 0 && groups[i].name.rfind("P1 ", 0) == 0) {
      EXPECT_EQ(groups[i - 1].name.rfind("P1 ", 0), 0u) << "P1 groups come first";
    }
  }
  // No data under the root: P1 and P2 give no group, P3 is rendered.
  s.dataRoot = "/nonexistent/lidar_sgm_data";
  const std::vector<FrameGroup> synthOnly = loadGroups(s);
  ASSERT_EQ(synthOnly.size(), 1u);
  EXPECT_EQ(synthOnly[0].name, "P3 clear 64 beams");
}

TEST(Groups, UnknownNamesAreRefused) {
  GroupSelection s = tinySelection();
  s.protocols = {"P4"};
  EXPECT_THROW(loadGroups(s), std::invalid_argument);
  s.protocols = {"P3"};
  s.p3Sets = {"fog64"};
  try {
    loadGroups(s);
    FAIL() << "an unknown P3 set was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown P3 set 'fog64'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
