// lidar_sgm_batch's pieces: the manifest's JSON lines and what a re-run carries over from earlier
// manifests.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/frame_list_fixture.hpp"
#include "batch/output_state.hpp"
#include "lidar_sgm/sequence/manifest.hpp"

namespace lidar_sgm {
namespace apps {
namespace {
namespace fs = std::filesystem;

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
