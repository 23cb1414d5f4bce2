// The GT against the frame's own scan, per object, and Table II without the objects off it.
#include <gtest/gtest.h>

#include "lidar_sgm/eval/metrics.hpp"
#include "lidar_sgm/eval/scan_agreement.hpp"

namespace lidar_sgm {
namespace {

// A 40 x 2 frame: object 1 (columns 0-19) has GT 50 px and its scan says 53.5 px (off the scan:
// median +3.5); object 2 (columns 20-29) has GT 20 and a scan at 20.25 (on it); columns 30-39 are
// background with a scan equal to the GT; row 1 has no scan.
struct Frame {
  Image<std::int16_t> scan{40, 2, kInvalidDisparity};
  Image<float> gt{40, 2, 0.0f};
  Image<std::uint8_t> objects{40, 2, 0};
  Frame() {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 40; ++x) {
        const int object = x < 20 ? 1 : x < 30 ? 2 : 0;
        objects(x, y) = static_cast<std::uint8_t>(object);
        gt(x, y) = object == 1 ? 50.0f : object == 2 ? 20.0f : 10.0f;
        if (y == 0) scan(x, y) = static_cast<std::int16_t>(object == 1 ? 53 * 16 + 8 : object == 2 ? 20 * 16 + 4 : 160);
      }
    }
  }
};

TEST(ScanAgreement, GivesEachObjectsMedianOfScanMinusGroundTruth) {
  Frame f;
  f.scan(0, 0) = 50 * 16;  // one scan pixel of object 1 agrees: the median does not move
  const auto agreement = eval::scanAgreement(f.scan.view(), f.gt.view(), f.objects.view());
  ASSERT_EQ(agreement.size(), 2u);
  EXPECT_EQ(agreement[0].object, 1);
  EXPECT_EQ(agreement[0].points, 20);
  EXPECT_DOUBLE_EQ(agreement[0].medianDifference, 3.5);
  EXPECT_TRUE(agreement[0].offTheScan());
  EXPECT_EQ(agreement[1].object, 2);
  EXPECT_EQ(agreement[1].points, 10);
  EXPECT_DOUBLE_EQ(agreement[1].medianDifference, 0.25);
  EXPECT_FALSE(agreement[1].offTheScan());
}

TEST(ScanAgreement, TooFewPointsGiveNoVerdict) {
  eval::ObjectScanAgreement few{1, eval::kScanAgreementMinPoints - 1, 10.0};
  EXPECT_FALSE(few.offTheScan());
  few.points = eval::kScanAgreementMinPoints;
  EXPECT_TRUE(few.offTheScan());
  // A scan farther than its GT is the LiDAR seeing past the object, not a GT fault.
  few.medianDifference = -10.0;
  EXPECT_FALSE(few.offTheScan());
}

TEST(ScanAgreement, TableTwoWithoutTheObjectsOffTheScan) {
  Frame f;
  const auto agreement = eval::scanAgreement(f.scan.view(), f.gt.view(), f.objects.view());
  const Image<std::uint8_t> off = eval::offTheScanPixels(f.objects.view(), agreement);
  ASSERT_FALSE(off.empty());
  EXPECT_EQ(off(0, 1), 1);
  EXPECT_EQ(off(25, 0), 0);
  EXPECT_EQ(off(35, 0), 0);
  // An estimate that follows the scan: object 1 wrong (3.5 px > 3 and > 5 % of 50), the rest right.
  const Image<std::int16_t>& estimate = f.scan;
  Image<std::int16_t> dense(40, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 40; ++x) dense(x, y) = estimate(x, 0);
  }
  const eval::ObjectSplitMetrics all = eval::evaluateObjectSplit(dense.view(), f.gt.view(), f.objects.view());
  EXPECT_DOUBLE_EQ(all.foreground, 40.0 / 60.0);
  const eval::ObjectSplitMetrics onScan =
      eval::evaluateObjectSplit(dense.view(), f.gt.view(), f.objects.view(), off.view());
  EXPECT_EQ(onScan.gtPixels, 40);
  EXPECT_DOUBLE_EQ(onScan.foreground, 0.0);
  EXPECT_DOUBLE_EQ(onScan.total, 0.0);
  // No object off its scan: no mask.
  f.scan(0, 0) = kInvalidDisparity;
  for (int x = 0; x < 20; ++x) f.scan(x, 0) = 50 * 16;
  EXPECT_TRUE(eval::offTheScanPixels(f.objects.view(),
                                     eval::scanAgreement(f.scan.view(), f.gt.view(), f.objects.view()))
                  .empty());
}

TEST(ScanAgreement, RejectsMismatchedSizes) {
  Frame f;
  Image<float> small(3, 2, 1.0f);
  EXPECT_THROW(eval::scanAgreement(f.scan.view(), small.view(), f.objects.view()), std::invalid_argument);
  EXPECT_THROW(eval::evaluateObjectSplit(f.scan.view(), f.gt.view(), f.objects.view(), Image<std::uint8_t>(3, 2).view()),
               std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
