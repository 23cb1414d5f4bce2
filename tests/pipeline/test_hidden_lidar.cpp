// The hidden-LiDAR filter (hidden_lidar.hpp): a point behind the surface a stereo-only match sees
// at its pixel is left out of the fused matching; points stereo agrees with, sees farther than, or
// has no disparity for are kept; the Densifier runs the stereo witness only in fused mode.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"
#include "lidar_sgm/pipeline/hidden_lidar.hpp"

namespace lidar_sgm {
namespace {

constexpr int kWidth = 200;
constexpr int kHeight = 60;
constexpr double kDisparity = 20.0;

int x16(double d) { return static_cast<int>(d * 16); }

TEST(HiddenLidar, OnlyPointsBehindTheStereoSurfaceByTheGapAreDropped) {
  Image<std::int16_t> stereo(40, 10, static_cast<std::int16_t>(x16(kDisparity)));
  for (int x = 0; x < 40; ++x) {
    stereo(x, 2) = static_cast<std::int16_t>(x16(104.0));
    stereo(x, 3) = static_cast<std::int16_t>(x16(106.0));
    stereo(x, 7) = kInvalidDisparity;
  }
  stereo(5, 5) = kInvalidDisparity;
  // Row 8: a near object from column 20 on; stereo has fattened it over columns 18 and 19.
  for (int x = 18; x < 40; ++x) stereo(x, 8) = static_cast<std::int16_t>(x16(40.0));
  std::vector<LidarSample> samples{
      {1, 1, x16(kDisparity)},  // agrees
      {2, 1, x16(15.0)},        // 5 px (25 %) behind what stereo sees: hidden
      {3, 1, x16(18.5)},        // 1.5 px behind: within the gap
      {4, 1, x16(30.0)},        // in front of the stereo surface: stereo is not trusted that way
      {10, 7, x16(5.0)},        // no stereo disparity in the window: no witness
      {5, 5, x16(15.0)},        // its own pixel has none (occluded for stereo): no witness
      {45, 5, x16(5.0)},        // outside the image
      {30, 2, x16(100.0)},      // 4 px behind, but under 5 % of its disparity
      {31, 3, x16(100.0)},      // 6 px and 6 % behind: hidden
      {33, 3, x16(106.0)},      // ... behind the surface this point vouches for
      {18, 8, x16(kDisparity)}, // the background beside the fattened edge: column 16 sees it
      {23, 8, x16(kDisparity)}, // behind the object, 3 columns in: hidden
      {24, 8, x16(40.0)},       // the object's own point, vouching for its surface
      {10, 9, x16(10.0)},       // 10 px behind, but no point vouches for the nearer surface
  };
  const auto hiddenOnes = [](const std::vector<LidarSample>& before, const std::vector<LidarSample>& after) {
    std::vector<std::pair<int, int>> gone;
    for (const LidarSample& s : before) {
      bool kept = false;
      for (const LidarSample& k : after) kept = kept || (k.x == s.x && k.y == s.y);
      if (!kept) gone.emplace_back(s.x, s.y);
    }
    return gone;
  };
  // The frame's scan: the samples that lie in the image.
  std::vector<LidarSample> inside;
  for (const LidarSample& s : samples) {
    if (s.x < stereo.width() && s.y < stereo.height()) inside.push_back(s);
  }
  const LidarPoints scan(stereo.width(), stereo.height(), inside);
  HiddenLidarOptions options;
  std::vector<LidarSample> kept = samples;
  EXPECT_EQ(dropHiddenLidar(stereo.view(), scan, kept, options), 3u);
  EXPECT_EQ(hiddenOnes(samples, kept), (std::vector<std::pair<int, int>>{{2, 1}, {31, 3}, {23, 8}}));
  options.minGap = 1.0;  // now the 1.5 px one is hidden too
  kept = samples;
  EXPECT_EQ(dropHiddenLidar(stereo.view(), scan, kept, options), 4u);
  options = {};
  options.supportHalfWidth = 1;  // (31, 3)'s voucher, two columns away, is too far now
  options.supportHalfHeight = 0;
  kept = samples;
  EXPECT_EQ(dropHiddenLidar(stereo.view(), scan, kept, options), 2u);
  EXPECT_EQ(hiddenOnes(samples, kept), (std::vector<std::pair<int, int>>{{2, 1}, {23, 8}}));
  options = {};
  options.halfWidth = 0;  // the point's own pixel alone: the fattened edge hides the background point
  kept = samples;
  EXPECT_EQ(hiddenOnes(samples, kept), (std::vector<std::pair<int, int>>{}));  // nothing dropped yet
  EXPECT_EQ(dropHiddenLidar(stereo.view(), scan, kept, options), 4u);
  EXPECT_EQ(hiddenOnes(samples, kept), (std::vector<std::pair<int, int>>{{2, 1}, {31, 3}, {18, 8}, {23, 8}}));
  options.enabled = false;
  kept = samples;
  EXPECT_EQ(dropHiddenLidar(stereo.view(), scan, kept, options), 0u);
  EXPECT_EQ(kept.size(), samples.size());
}

TEST(HiddenLidar, ImpossibleOptionsAreNamed) {
  const auto message = [](const HiddenLidarOptions& o) {
    DensifierConfig config;
    config.hiddenLidar = o;
    return validationError(config);
  };
  HiddenLidarOptions o;
  EXPECT_EQ(message(o), "");
  o.minGap = 0.0;
  EXPECT_NE(message(o).find("minGap"), std::string::npos) << message(o);
  o = {};
  o.relativeGap = -0.1;
  EXPECT_NE(message(o).find("relativeGap"), std::string::npos) << message(o);
  o = {};
  o.halfWidth = -1;
  EXPECT_NE(message(o).find("halfWidth"), std::string::npos) << message(o);
  o = {};
  o.supportHalfHeight = 65;
  EXPECT_NE(message(o).find("supportHalfHeight"), std::string::npos) << message(o);
  o = {};
  o.witnessScale = 0.3f;
  EXPECT_NE(message(o).find("witnessScale"), std::string::npos) << message(o);
  o = {};
  o.witnessMarginRows = -1;
  EXPECT_NE(message(o).find("witnessMarginRows"), std::string::npos) << message(o);
  o.witnessMarginRows = 4097;
  EXPECT_NE(message(o).find("witnessMarginRows"), std::string::npos) << message(o);
  o = {};
  o.witnessScale = 0.3f;
  EXPECT_THROW(validate(o), std::invalid_argument);
}

TEST(HiddenLidar, TheWitnessRowsSpanThePointsWithTheMarginOnWholeBlocks) {
  const auto rows = [](const std::vector<LidarSample>& samples, int margin, int block) {
    const WitnessRows r = witnessRows(samples, 100, margin, block);
    return std::pair<int, int>(r.begin, r.end);
  };
  using Rows = std::pair<int, int>;
  EXPECT_EQ(rows({}, 16, 1), Rows(0, 0));                     // no point: nothing to match
  EXPECT_EQ(rows({{5, -1, 16}, {5, 100, 16}}, 16, 1), Rows(0, 0));  // rows outside the image are never read
  const std::vector<LidarSample> band = {{3, 41, 16}, {7, 30, 16}, {9, 52, 16}};
  EXPECT_EQ(rows(band, 0, 1), Rows(30, 53));
  EXPECT_EQ(rows(band, 5, 1), Rows(25, 58));
  EXPECT_EQ(rows(band, 5, 4), Rows(24, 60));  // begin down, end up to a multiple of the block
  EXPECT_EQ(rows(band, 5, 8), Rows(24, 64));
  EXPECT_EQ(rows(band, 40, 1), Rows(0, 93));     // clamped at the top
  EXPECT_EQ(rows(band, 4096, 8), Rows(0, 100));  // and at the bottom, even off a block
}

/// A textured plane at kDisparity with a stripe of LiDAR points far behind it (the background an
/// object's edge hides from the camera but not from the LiDAR, a few pixels wide) in a scan of
/// right points.
struct BledScan {
  test::SyntheticStereo stereo = test::makeStereo(kWidth, kHeight, [](double, double) { return kDisparity; });
  std::vector<LidarSample> samples;
  static bool inBlock(int x, int y) { return x >= 100 && x < 108 && y >= 20 && y < 40; }
  BledScan() {
    for (int y = 4; y < kHeight - 4; y += 2) {
      for (int x = 40; x < kWidth - 4; ++x) samples.push_back({x, y, x16(inBlock(x, y) ? kDisparity - 12.0 : kDisparity)});
    }
  }
};

struct Outcome {
  int wrongInBlock = 0;
  std::size_t hidden = 0;
  double witnessMs = 0.0;
};

Outcome densify(const BledScan& scan, bool filter, float witnessScale, bool withLidar = true, bool withPair = true) {
  const LidarPoints lidar(kWidth, kHeight, scan.samples);
  Densifier densifier;
  DensifierConfig config;
  config.computeCloud = false;
  config.matcher.numDisparities = 48;
  config.rangeMode = DisparityRangeMode::Fixed;
  config.hiddenLidar.enabled = filter;
  config.hiddenLidar.witnessScale = witnessScale;
  densifier.setConfig(config);
  if (withPair) densifier.setStereoPair(scan.stereo.left.view(), scan.stereo.right.view());
  densifier.runProjected(withLidar ? &lidar : nullptr);
  Outcome run;
  run.hidden = densifier.filterStats().hiddenLidar;
  run.witnessMs = densifier.timings().witness;
  for (int y = 20; y < 40; ++y) {
    for (int x = 100; x < 108; ++x) {
      const std::int16_t d = densifier.disparity()(x, y);
      run.wrongInBlock += d == kInvalidDisparity || std::abs(d / 16.0 - kDisparity) > 3.0 ? 1 : 0;
    }
  }
  return run;
}

TEST(HiddenLidar, TheDensifierLeavesHiddenPointsOutOfTheFusedMatching) {
  const BledScan scan;
  const Outcome off = densify(scan, false, 1.0f);
  EXPECT_EQ(off.hidden, 0u);
  EXPECT_EQ(off.witnessMs, 0.0);
  EXPECT_GT(off.wrongInBlock, 100);  // of 160 pixels, most follow the stripe's wrong points
  for (const float scale : {1.0f, 0.5f, 0.25f}) {
    const Outcome on = densify(scan, true, scale);
    EXPECT_GE(on.hidden, 60u) << "scale " << scale;  // most of the stripe's 80 points
    EXPECT_GT(on.witnessMs, 0.0);
    EXPECT_LT(on.wrongInBlock, off.wrongInBlock / 10) << "scale " << scale;
  }
}

TEST(HiddenLidar, AWitnessOnThePointsRowsDropsWhatTheWholeFrameWitnessDrops) {
  // A frame three times the scan's height: the witness on the points' rows and their margin
  // finds the same hidden points as over the whole frame, so the fused frames are identical.
  constexpr int kTall = 3 * kHeight;
  const test::SyntheticStereo stereo = test::makeStereo(kWidth, kTall, [](double, double) { return kDisparity; });
  std::vector<LidarSample> samples;
  for (int y = kHeight; y < 2 * kHeight; y += 2) {
    for (int x = 40; x < kWidth - 4; ++x) {
      const bool hidden = x >= 100 && x < 108 && y >= kHeight + 20 && y < kHeight + 40;
      samples.push_back({x, y, x16(hidden ? kDisparity - 12.0 : kDisparity)});
    }
  }
  const LidarPoints lidar(kWidth, kTall, samples);
  for (const float scale : {1.0f, 0.5f, 0.25f}) {
    Image<std::int16_t> disparity[2];
    std::size_t hidden[2] = {0, 0};
    for (const int margin : {16, 4096}) {
      DensifierConfig config;
      config.computeCloud = false;
      config.matcher.numDisparities = 48;
      config.rangeMode = DisparityRangeMode::Fixed;
      config.hiddenLidar.witnessScale = scale;
      config.hiddenLidar.witnessMarginRows = margin;
      Densifier densifier;
      densifier.setConfig(config);
      densifier.setStereoPair(stereo.left.view(), stereo.right.view());
      densifier.runProjected(&lidar);
      const int i = margin == 4096 ? 1 : 0;
      hidden[i] = densifier.filterStats().hiddenLidar;
      disparity[i] = Image<std::int16_t>(kWidth, kTall);
      for (int y = 0; y < kTall; ++y) {
        for (int x = 0; x < kWidth; ++x) disparity[i](x, y) = densifier.disparity()(x, y);
      }
    }
    EXPECT_GE(hidden[0], 60u) << "scale " << scale;
    EXPECT_EQ(hidden[0], hidden[1]) << "scale " << scale;
    int differing = 0;
    for (int y = 0; y < kTall; ++y) {
      for (int x = 0; x < kWidth; ++x) differing += disparity[0](x, y) != disparity[1](x, y) ? 1 : 0;
    }
    EXPECT_EQ(differing, 0) << "scale " << scale;
  }
}

TEST(HiddenLidar, NoWitnessWithoutBothInputs) {
  const BledScan scan;
  const Outcome stereoOnly = densify(scan, true, 1.0f, false, true);
  EXPECT_EQ(stereoOnly.hidden, 0u);
  EXPECT_EQ(stereoOnly.witnessMs, 0.0);
  const Outcome lidarOnly = densify(scan, true, 1.0f, true, false);
  EXPECT_EQ(lidarOnly.hidden, 0u);
  EXPECT_EQ(lidarOnly.witnessMs, 0.0);
}

}  // namespace
}  // namespace lidar_sgm
