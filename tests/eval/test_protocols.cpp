// The frames of protocols P1, P2, P3 (lidar_sgm/eval/protocols.hpp): every EvalFrame field filled and
// consistent, on the shared third-party data (skipped when absent) and on synthetic frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/test_data.hpp"
#include "eval/lidar_rings.hpp"
#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/eval/simulated_lidar.hpp"
#include "lidar_sgm/geometry/projection.hpp"
#include "lidar_sgm/io/calibration_io.hpp"
#include "lidar_sgm/io/cloud_io.hpp"
#include "lidar_sgm/io/image_io.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

std::size_t pixels(const EvalFrame& f) { return static_cast<std::size_t>(f.left.cols) * static_cast<std::size_t>(f.left.rows); }

/// a / b as a double (0 when b is 0).
double ratio(std::size_t a, std::size_t b) { return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0; }

std::size_t inputPixels(const EvalFrame& f) {
  std::size_t n = 0;
  for (int y = 0; y < f.lidar.height(); ++y) {
    for (int x = 0; x < f.lidar.width(); ++x) n += f.lidar.count(x, y) > 0;
  }
  return n;
}

std::size_t gtPixels(const EvalFrame& f) {
  std::size_t n = 0;
  for (int y = 0; y < f.groundTruth.height(); ++y) {
    for (int x = 0; x < f.groundTruth.width(); ++x) n += f.groundTruth(x, y) > 0.0f;
  }
  return n;
}

/// Min and max of the GT [px] over the pixels that have one.
std::pair<double, double> gtRange(const EvalFrame& f) {
  double lo = 1e9;
  double hi = 0.0;
  for (int y = 0; y < f.groundTruth.height(); ++y) {
    for (int x = 0; x < f.groundTruth.width(); ++x) {
      const float d = f.groundTruth(x, y);
      if (d > 0.0f) {
        lo = std::min(lo, static_cast<double>(d));
        hi = std::max(hi, static_cast<double>(d));
      }
    }
  }
  return {lo, hi};
}

/// Share of the GT pixels that have an input point within +-rx columns and +-ry rows (3x3: what
/// Eq. 4 looks at, i.e. how much of the GT the LiDAR cost sees directly).
double gtWithInputNeighbour(const EvalFrame& f, int rx = 1, int ry = 1) {
  std::size_t gt = 0;
  std::size_t near = 0;
  for (int y = 0; y < f.groundTruth.height(); ++y) {
    for (int x = 0; x < f.groundTruth.width(); ++x) {
      if (!(f.groundTruth(x, y) > 0.0f)) continue;
      ++gt;
      bool found = false;
      for (int dy = -ry; dy <= ry && !found; ++dy) {
        for (int dx = -rx; dx <= rx && !found; ++dx) {
          const int xx = x + dx;
          const int yy = y + dy;
          found = xx >= 0 && yy >= 0 && xx < f.lidar.width() && yy < f.lidar.height() && f.lidar.count(xx, yy) > 0;
        }
      }
      near += found;
    }
  }
  return ratio(near, gt);
}

/// Every field of an EvalFrame filled and consistent.
void expectWellFormed(const EvalFrame& f) {
  SCOPED_TRACE(f.dataset + "/" + f.name);
  ASSERT_FALSE(f.left.empty());
  EXPECT_EQ(f.left.channels(), 1);
  EXPECT_TRUE(f.left.depth() == CV_8U || f.left.depth() == CV_16U);
  EXPECT_EQ(f.right.size(), f.left.size());
  EXPECT_EQ(f.right.type(), f.left.type());
  EXPECT_EQ(f.leftColor.size(), f.left.size());
  EXPECT_EQ(f.leftColor.type(), CV_8UC3);
  const int w = f.left.cols;
  const int h = f.left.rows;
  EXPECT_EQ(f.groundTruth.width(), w);
  EXPECT_EQ(f.groundTruth.height(), h);
  ASSERT_EQ(f.lidar.width(), w);
  ASSERT_EQ(f.lidar.height(), h);
  ASSERT_EQ(f.lidarSparse.width(), w);
  ASSERT_EQ(f.lidarSparse.height(), h);
  ASSERT_EQ(f.exclude.width(), w);
  ASSERT_EQ(f.exclude.height(), h);
  EXPECT_FALSE(f.lidar.empty());
  EXPECT_GT(f.focalBaseline, 0.0);
  EXPECT_GE(f.numDisparities, 128);
  EXPECT_EQ(f.numDisparities % 16, 0);
  EXPECT_GT(f.numDisparities, gtRange(f).second);
  if (f.up.empty()) {
    EXPECT_EQ(f.upBaselineRatio, 0.0);
  } else {
    EXPECT_EQ(f.up.size(), f.left.size());
    EXPECT_EQ(f.up.type(), f.left.type());
    EXPECT_GT(f.upBaselineRatio, 0.0);
  }
  // exclude == the input pixels; lidarSparse == the nearest input point there.
  std::size_t mismatches = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int n = f.lidar.count(x, y);
      const int nearest = n ? *std::max_element(f.lidar.begin(x, y), f.lidar.end(x, y)) : kInvalidDisparity;
      mismatches += (f.exclude(x, y) != (n > 0 ? 1 : 0)) + (f.lidarSparse(x, y) != nearest);
      for (const int* d = f.lidar.begin(x, y); d != f.lidar.end(x, y); ++d) mismatches += *d <= 0;
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(Protocols, NumDisparitiesRule) {
  EXPECT_EQ(numDisparitiesFor(0.0), 128);
  EXPECT_EQ(numDisparitiesFor(64.0), 128);
  EXPECT_EQ(numDisparitiesFor(120.0), 128);
  EXPECT_EQ(numDisparitiesFor(124.1), 144);  // KITTI 2012 000001_10
  EXPECT_EQ(numDisparitiesFor(163.0), 176);
  // Half scale searches half the range, which must stay a multiple of 16: round up to 32.
  EXPECT_EQ(numDisparitiesAt(144, 1.0f), 144);
  EXPECT_EQ(numDisparitiesAt(128, 0.5f), 128);
  EXPECT_EQ(numDisparitiesAt(144, 0.5f), 160);
  EXPECT_EQ(numDisparitiesAt(176, 0.5f), 192);
  EXPECT_EQ(numDisparitiesAt(512, 0.5f), 512);
}

TEST(Protocols, SparseRowSplit) {
  // Rows 1..5 hold 3 points each, row 0 one point (below the minimum: always input).
  Image<std::int16_t> sparse(8, 6, kInvalidDisparity);
  sparse(2, 0) = 160;
  for (int y = 1; y < 6; ++y) {
    for (int x = 0; x < 3; ++x) sparse(x, y) = static_cast<std::int16_t>(16 * (10 + y));
  }
  Image<std::int16_t> input;
  Image<std::int16_t> heldOut;
  splitSparseRows(sparse, input, heldOut, 3, 2, 1);  // beam rows 1..5 -> indices 0..4; odd ones held out
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      const bool valid = sparse(x, y) != kInvalidDisparity;
      const bool held = valid && (y == 2 || y == 4);
      EXPECT_EQ(heldOut(x, y), held ? sparse(x, y) : kInvalidDisparity) << x << "," << y;
      EXPECT_EQ(input(x, y), valid && !held ? sparse(x, y) : kInvalidDisparity) << x << "," << y;
    }
  }
}

TEST(Protocols, RingSplitIsDisjoint) {
  std::vector<Eigen::Vector3f> points(12, Eigen::Vector3f(1.0f, 0.0f, 0.0f));
  std::vector<int> rings;
  for (int i = 0; i < 12; ++i) rings.push_back(i / 2);  // rings 0..5, 2 points each
  const RingSplit s = splitByRing(points, rings);
  EXPECT_EQ(s.rings, 6);
  EXPECT_EQ(s.heldOut.size(), 2u);  // ring 3
  EXPECT_EQ(s.input.size(), 10u);
  EXPECT_EQ(s.heldOutIndex, (std::vector<std::size_t>{6, 7}));
  for (const int r : s.inputRings) EXPECT_NE(r % 4, 3);
  EXPECT_THROW(splitByRing(points, rings, 4, 4), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------ P1

class ProtocolP1 : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { frames_ = new std::vector<EvalFrame>(loadP1(test::sharedDataRoot())); }
  static void TearDownTestSuite() {
    delete frames_;
    frames_ = nullptr;
  }
  static std::vector<EvalFrame>* frames_;
};
std::vector<EvalFrame>* ProtocolP1::frames_ = nullptr;

TEST_F(ProtocolP1, FramesPerDatasetSortedAndWellFormed) {
  const std::map<std::string, std::pair<std::string, std::size_t>> expected{
      {"kitti2015", {"kitti_stereo2015_training_sample", 2}},
      {"kitti2012", {"kitti_stereo2012_training_sample", 2}},
      {"drivingstereo", {"drivingstereo_sample", 4}},
      {"middlebury", {"middlebury_stereo_sample", 5}}};
  std::map<std::string, std::size_t> counts;
  for (const EvalFrame& f : *frames_) ++counts[f.dataset];
  std::size_t present = 0;
  for (const auto& [dataset, folderAndCount] : expected) {
    if (!test::haveSharedData(folderAndCount.first)) {
      EXPECT_EQ(counts.count(dataset), 0u);
      continue;
    }
    ++present;
    EXPECT_EQ(counts[dataset], folderAndCount.second) << dataset;
  }
  EXPECT_EQ(counts.size(), present);
  if (present == 0) GTEST_SKIP() << "no P1 data under " << test::sharedDataRoot();

  for (std::size_t i = 1; i < frames_->size(); ++i) {
    const EvalFrame& a = (*frames_)[i - 1];
    const EvalFrame& b = (*frames_)[i];
    EXPECT_TRUE(a.dataset < b.dataset || (a.dataset == b.dataset && a.name < b.name)) << b.dataset << "/" << b.name;
  }
  for (const EvalFrame& f : *frames_) {
    expectWellFormed(f);
    EXPECT_EQ(f.protocol, "P1");
    EXPECT_FALSE(f.denseGroundTruth);  // sparse GT: a pixel without GT was not measured
    EXPECT_TRUE(f.up.empty());
    const auto [lo, hi] = gtRange(f);
    const double gtShare = ratio(gtPixels(f), pixels(f));
    const double inputShare = ratio(inputPixels(f), pixels(f));
    std::printf("  P1 %-13s %-45s %4dx%-3d GT %5.1f %% %6.2f..%6.2f px  LiDAR %5.2f %% of pixels  "
                "depth %.1f..%.1f m  %d disparities\n",
                f.dataset.c_str(), f.name.c_str(), f.left.cols, f.left.rows, 100 * gtShare, lo, hi, 100 * inputShare,
                f.focalBaseline / hi, f.focalBaseline / lo, f.numDisparities);
    SCOPED_TRACE(f.dataset + "/" + f.name);
    EXPECT_GT(gtShare, 0.15);
    EXPECT_GT(lo, 1.0);
    EXPECT_LT(hi, 130.0);
    EXPECT_GT(f.focalBaseline / hi, 0.9);  // depths in a realistic range for IP-Basic
    EXPECT_LT(f.focalBaseline / lo, 125.0);
    if (f.dataset.rfind("kitti", 0) == 0) {
      EXPECT_GT(inputShare, 0.01);
      EXPECT_LT(inputShare, 0.035);  // KITTI 2012 000000_10: 3.3 % (its GT is dense: 36 %)
    } else {
      EXPECT_GT(inputShare, 0.003);
    }
    if (f.dataset == "middlebury") {
      EXPECT_LT(f.focalBaseline / lo, 80.0);
    }
  }
}

TEST_F(ProtocolP1, Kitti2015MatchesTheP1TestsSimulation) {
  const std::string folder = "kitti_stereo2015_training_sample";
  if (!test::haveSharedData(folder)) GTEST_SKIP() << "no " << folder;
  const auto it = std::find_if(frames_->begin(), frames_->end(), [](const EvalFrame& f) {
    return f.dataset == "kitti2015" && f.name == "000000_10";
  });
  ASSERT_NE(it, frames_->end());
  // What tests/eval/test_kitti_p1.cpp builds.
  const Image<float> gt =
      io::readKittiDisparityFloat(test::sharedDataRoot() + "/" + folder + "/disp_occ_0/000000_10.png");
  Image<std::uint8_t> inputMask;
  const LidarPoints lidar = eval::simulateLidarFromGroundTruth(gt.view(), {}, inputMask);
  ASSERT_EQ(it->lidar.size(), lidar.size());
  std::size_t mismatches = 0;
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      mismatches += it->exclude(x, y) != inputMask(x, y) || it->lidar.count(x, y) != lidar.count(x, y) ||
                    it->groundTruth(x, y) != gt(x, y);
      if (lidar.count(x, y) == 1 && it->lidar.count(x, y) == 1) mismatches += *lidar.begin(x, y) != *it->lidar.begin(x, y);
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(it->numDisparities, 128);
  EXPECT_NEAR(it->focalBaseline, 389.63, 0.01);
}

// ------------------------------------------------------------------------------------------ P2

TEST(ProtocolP2, RingAndRowHoldOut) {
  const bool rings = test::haveSharedData("kitti_stereo_lidar_calib_nogt");
  const bool sparse = test::haveSharedData("kitti_stereo_sparse_lidar_disparity_sample");
  if (!rings && !sparse) GTEST_SKIP() << "no P2 data under " << test::sharedDataRoot();
  const std::vector<EvalFrame> frames = loadP2(test::sharedDataRoot());
  ASSERT_EQ(frames.size(), (rings ? 2u : 0u) + (sparse ? 1u : 0u));
  for (const EvalFrame& f : frames) {
    expectWellFormed(f);
    SCOPED_TRACE(f.dataset + "/" + f.name);
    EXPECT_EQ(f.protocol, "P2");
    EXPECT_FALSE(f.denseGroundTruth);  // held-out rings: sparse
    const auto [lo, hi] = gtRange(f);
    EXPECT_GE(lo, 0.5);
    EXPECT_LE(hi, 200.0);
    const std::size_t gt = gtPixels(f);
    const std::size_t in = inputPixels(f);
    std::size_t both = 0;
    for (int y = 0; y < f.groundTruth.height(); ++y) {
      for (int x = 0; x < f.groundTruth.width(); ++x) both += f.groundTruth(x, y) > 0.0f && f.exclude(x, y);
    }
    std::printf("  P2 %-12s %-25s input %5zu px (%.2f %% of pixels), GT %5zu px (%.1f %% of GT+input), "
                "%zu px both; GT %.1f..%.1f px; GT px with input in 3x3 %.1f %%, in 17x3 %.1f %%; %d disparities\n",
                f.dataset.c_str(), f.name.c_str(), in, 100 * ratio(in, pixels(f)), gt, 100 * ratio(gt, gt + in), both, lo, hi,
                100 * gtWithInputNeighbour(f), 100 * gtWithInputNeighbour(f, 8, 1), f.numDisparities);
    EXPECT_GT(ratio(gt, gt + in), 0.15);
    EXPECT_LT(ratio(gt, gt + in), 0.35);
    EXPECT_LT(ratio(both, gt), 0.05);
    EXPECT_NEAR(f.focalBaseline, 721.5377 * 0.54, 6.0);  // the calibration's b is 0.5327 m
    EXPECT_LT(gtWithInputNeighbour(f), 0.05);  // held out between the input beams, not next to them
  }
  if (!rings) return;
  EXPECT_EQ(frames[0].name, "densedepthmap_0000000001");
  EXPECT_EQ(frames[1].name, "stereo_rcnn_demo");
  // Input and GT come from disjoint rings; every 4th ring is held out; the GT is ~1/4 of the
  // points the full scan projects.
  const std::string root = test::sharedDataRoot() + "/kitti_stereo_lidar_calib_nogt/";
  for (int i = 0; i < 2; ++i) {
    const EvalFrame& f = frames[static_cast<std::size_t>(i)];
    const std::vector<Eigen::Vector3f> points = toPoints(io::readKittiBin(root + "velodyne/" + f.name + ".bin"));
    const RingSplit split = splitByRing(points, recoverRings(points));
    const std::set<int> inputRings(split.inputRings.begin(), split.inputRings.end());
    const std::set<int> heldOutRings(split.heldOutRings.begin(), split.heldOutRings.end());
    EXPECT_EQ(inputRings.size(), 48u);
    EXPECT_EQ(heldOutRings.size(), 16u);
    for (const int r : heldOutRings) EXPECT_EQ(inputRings.count(r), 0u) << r;
    const geometry::StereoCalibration calibration =
        io::readCalibration(root + "calib/" + f.name + ".txt", f.left.cols, f.left.rows);
    const geometry::ProjectedLidar all = geometry::project(points, calibration);
    const geometry::ProjectedLidar input = geometry::project(split.input, calibration);
    const geometry::ProjectedLidar heldAlone = geometry::project(split.heldOut, calibration);
    EXPECT_EQ(f.lidar.size(), input.samples.size());
    const double share = ratio(gtPixels(f), all.samples.size());
    std::printf("  P2 %s: scan projects %zu points; GT %zu px = %.1f %% of them (held-out rings alone would keep "
                "%zu of %zu in view: the whole-scan occlusion filter drops %zu more)\n",
                f.name.c_str(), all.samples.size(), gtPixels(f), 100 * share, heldAlone.samples.size(),
                heldAlone.samples.size() + heldAlone.stats.occluded, heldAlone.samples.size() - gtPixels(f));
    EXPECT_GT(share, 0.18);
    EXPECT_LT(share, 0.32);
  }
}

// ------------------------------------------------------------------------------------------ P3

class ProtocolP3 : public ::testing::TestWithParam<P3Options> {};

TEST_P(ProtocolP3, SmallFrame) {
  P3Options o = GetParam();
  o.frames = 1;
  o.width = 310;
  o.height = 94;
  const std::vector<EvalFrame> frames = loadP3(o);
  ASSERT_EQ(frames.size(), 1u);
  const EvalFrame& f = frames[0];
  expectWellFormed(f);
  EXPECT_EQ(f.protocol, "P3");
  EXPECT_TRUE(f.denseGroundTruth);  // GT 0 is sky: a point there is wrong
  EXPECT_EQ(f.dataset, p3DatasetName(o));
  EXPECT_EQ(f.name, "000100");
  EXPECT_EQ(f.left.cols, 310);
  EXPECT_EQ(f.left.rows, 94);
  EXPECT_EQ(f.left.depth(), CV_8U);
  if (o.thirdCamera) {
    EXPECT_FALSE(f.up.empty());
    EXPECT_NEAR(f.upBaselineRatio, 0.20 / 0.54, 1e-9);
  } else {
    EXPECT_TRUE(f.up.empty());
    EXPECT_EQ(f.upBaselineRatio, 0.0);
  }
  EXPECT_NEAR(f.focalBaseline, 721.5377 * 310 / 1242 * 0.54, 0.01);
  const double gtShare = ratio(gtPixels(f), pixels(f));
  EXPECT_GT(gtShare, 0.5);
  // The scan, projected with the written calibration, agrees with the exact GT.
  std::size_t compared = 0;
  std::size_t agree = 0;
  for (int y = 0; y < f.left.rows; ++y) {
    for (int x = 0; x < f.left.cols; ++x) {
      if (f.lidar.count(x, y) == 0 || !(f.groundTruth(x, y) > 0.0f)) continue;
      ++compared;
      agree += std::abs(f.lidarSparse(x, y) / 16.0 - f.groundTruth(x, y)) < 1.0;
    }
  }
  const double inputShare = ratio(inputPixels(f), pixels(f));
  std::printf("  P3 %-20s %zu LiDAR points on %.1f %% of pixels, GT %.1f %%, %.1f %% of the input within 1 px of GT\n",
              f.dataset.c_str(), f.lidar.size(), 100 * inputShare, 100 * gtShare,
              100 * ratio(agree, compared));
  EXPECT_GT(inputShare, 0.02);
  ASSERT_GT(compared, 100u);
  EXPECT_GT(ratio(agree, compared), 0.9);
}

P3Options variant(bool rain, int beams, bool thirdCamera) {
  P3Options o;
  o.rain = rain;
  o.beams = beams;
  o.thirdCamera = thirdCamera;
  return o;
}

INSTANTIATE_TEST_SUITE_P(Variants, ProtocolP3,
                         ::testing::Values(variant(false, 64, false), variant(true, 64, false),
                                           variant(false, 128, false), variant(true, 128, true)),
                         [](const ::testing::TestParamInfo<P3Options>& paramInfo) { return p3DatasetName(paramInfo.param); });

TEST(ProtocolP3Names, DatasetNames) {
  EXPECT_EQ(p3DatasetName(variant(false, 64, false)), "synth_clear_64");
  EXPECT_EQ(p3DatasetName(variant(true, 128, false)), "synth_rain_128");
  EXPECT_EQ(p3DatasetName(variant(false, 64, true)), "synth_clear_64_3cam");
  P3Options none;
  none.frames = 0;
  EXPECT_TRUE(loadP3(none).empty());
  none.frames = -1;
  EXPECT_THROW(loadP3(none), std::invalid_argument);
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
