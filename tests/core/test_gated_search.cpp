// The LiDAR-gated search (Parameters::gatedSearch): the gate (lidarSearchWindows) by hand, the
// windowed stages (gated_stages.hpp) against the ungated ones on full windows and against a
// brute-force oracle on random windows, and whole frames where the gate must keep the right
// disparity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends/common/gated_stages.hpp"
#include "backends/common/lidar_search_windows.hpp"
#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace {

struct Window {
  int first;
  int count;
};

Window windowAt(const SearchWindows& w, int x, int y) { return {w.first(x, y), w.count(x, y)}; }

void expectWindow(const SearchWindows& w, int x, int y, int first, int count) {
  EXPECT_EQ(w.first(x, y), first) << "(" << x << ", " << y << ")";
  EXPECT_EQ(w.count(x, y), count) << "(" << x << ", " << y << ")";
}

TEST(LidarSearchWindows, WindowsByHand) {
  // 40x30, D = 64 from minDisparity 0, margin 2, rows 3.
  const LidarPoints points(40, 30,
                           {{5, 5, 20 * 16},                      // 20 px: [18, 22] -> 16 wide
                            {20, 5, 62 * 16},                     // 62 px: [60, 63] -> moved down to [48, 64)
                            {30, 5, 10 * 16}, {30, 7, 40 * 16},   // 10 and 40 px: [8, 42] -> 48 wide
                            {10, 20, 328},                        // 20.5 px: [18, 23]
                            {25, 20, 1 * 16}});                   // 1 px: [0, 3]
  SearchWindows w;
  lidarSearchWindows(points, 0, 64, 3, 2, w);
  ASSERT_EQ(w.width(), 40);
  ASSERT_EQ(w.numDisparities(), 64);
  expectWindow(w, 5, 5, 18, 16);
  expectWindow(w, 20, 5, 48, 16);
  expectWindow(w, 30, 6, 8, 48);
  expectWindow(w, 10, 20, 18, 16);
  expectWindow(w, 25, 20, 0, 16);
  // The neighbourhood: +-1 column, +-3 rows.
  expectWindow(w, 4, 8, 18, 16);
  expectWindow(w, 6, 2, 18, 16);
  expectWindow(w, 3, 5, 0, 64);
  expectWindow(w, 5, 9, 0, 64);
  expectWindow(w, 5, 1, 0, 64);
  // Far from every point: the full range.
  expectWindow(w, 0, 29, 0, 64);
  expectWindow(w, 15, 13, 0, 64);
}

TEST(LidarSearchWindows, TheRangesOffsetAndPointsOutsideIt) {
  // minDisparity 4, D = 32: disparity 20 is index 16; a point at 2 px (below the range even with
  // its margin) does not gate; one at 60 px (above it) neither.
  const LidarPoints points(30, 10, {{5, 5, 20 * 16}, {15, 5, 2 * 16}, {25, 5, 60 * 16}});
  SearchWindows w;
  lidarSearchWindows(points, 4, 32, 0, 1, w);
  expectWindow(w, 5, 5, 15, 16);  // [19, 21] -> indices [15, 17] -> [15, 31)
  expectWindow(w, 5, 6, 0, 32);   // rows 0: only the point's own row
  expectWindow(w, 15, 5, 0, 32);
  expectWindow(w, 25, 5, 0, 32);
  // A margin as wide as the range gives the full range back.
  lidarSearchWindows(points, 4, 32, 0, 512, w);
  expectWindow(w, 5, 5, 0, 32);
  expectWindow(w, 15, 5, 0, 32);
}

TEST(LidarSearchWindows, DisparitiesBeyondSixteenBitsKeepTheirSide) {
  // The gate works on x16 disparities clamped to 16 bits: a point at 3000 px (48000 x16) beside
  // one at 20 px still bounds its neighbours' window from above by the range's end, not below.
  const LidarPoints points(20, 10, {{5, 5, 20 * 16}, {6, 5, 3000 * 16}});
  SearchWindows w;
  lidarSearchWindows(points, 0, 64, 0, 2, w);
  expectWindow(w, 5, 5, 16, 48);  // [18, 63] -> 48 wide, moved down to end at 64
  expectWindow(w, 7, 5, 0, 64);   // only the far point: outside the range, no gate
}

TEST(GatedPathCost, TermsOutsideThePreviousWindowAreAbsent) {
  // Previous window [4, 8) with L = 30, 10, 40, 50: M = 10. P1 = 3, P2 = 20.
  const std::uint16_t previous[4] = {30, 10, 40, 50};
  const int P1 = 3;
  const int P2 = 20;
  // d = 5: min(L(5) = 10, L(4) + 3 = 33, L(6) + 3 = 43, 10 + 20) - 10 = 0.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 5, 10, P1, P2), 7);
  // d = 8 (outside): only L(7) + P1 = 53 and M + P2 = 30 are present.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 8, 10, P1, P2), 7 + 20);
  // d = 3 (outside, next to 4): L(4) + P1 = 33 against M + P2 = 30.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 3, 10, P1, P2), 7 + 20);
  // d = 12 (far outside): M + P2 only.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 12, 10, P1, P2), 7 + 20);
  // With a large P2, the P1 neighbour wins at d = 3 and d = 8.
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 3, 10, P1, 100), 7 + 33 - 10);
  EXPECT_EQ(cpu_ref::pathCostStep(7, previous, 4, 4, 8, 10, P1, 100), 7 + 53 - 10);
}

MatchingCostVolume randomCost(int width, int height, int D, unsigned seed) {
  MatchingCostVolume cost(width, height, D);
  std::mt19937 engine(seed);
  for (std::size_t i = 0; i < cost.size(); ++i) cost.data()[i] = static_cast<std::uint8_t>(engine() % 63u);
  return cost;
}

// Random windows, multiples of 16 wide, some full.
SearchWindows randomWindows(int width, int height, int D, unsigned seed) {
  SearchWindows w;
  w.resizeFull(width, height, D);
  std::mt19937 engine(seed);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int count = 16 * (1 + static_cast<int>(engine() % static_cast<unsigned>(D / 16)));
      const int first = static_cast<int>(engine() % static_cast<unsigned>(D - count + 1));
      w.set(x, y, first, count);
    }
  }
  return w;
}

TEST(GatedStages, FullWindowsGiveTheUngatedStagesBitForBit) {
  const int width = 37, height = 23, D = 48, minDisparity = -3;
  const MatchingCostVolume cost = randomCost(width, height, D, 11);
  SearchWindows windows;
  windows.resizeFull(width, height, D);
  WindowedMatchingCost windowed;
  windowed.resize(windows);
  cpu_ref::restrictToWindows(cost, windowed);
  for (const int paths : {4, 8}) {
    SCOPED_TRACE(paths);
    AggregatedCostVolume sum;
    cpu_ref::aggregatePaths(cost, 7, 70, paths, sum);
    WindowedAggregatedCost windowedSum;
    cpu_ref::aggregatePaths(windowed, 7, 70, paths, windowedSum);
    ASSERT_EQ(windowedSum.size(), sum.size());
    EXPECT_TRUE(std::equal(sum.data(), sum.data() + sum.size(), windowedSum.data()));

    for (const int uniqueness : {0, 5}) {
      Image<std::int16_t> d16(width, height), best(width, height), d16w(width, height), bestW(width, height);
      cpu_ref::selectDisparity(sum, minDisparity, uniqueness, true, {d16.view(), best.view()});
      cpu_ref::selectDisparity(windowedSum, minDisparity, uniqueness, true, {d16w.view(), bestW.view()});
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          ASSERT_EQ(d16w(x, y), d16(x, y)) << x << "," << y;
          ASSERT_EQ(bestW(x, y), best(x, y)) << x << "," << y;
        }
      }
      Image<std::uint8_t> margin(width, height), marginW(width, height);
      Image<std::uint16_t> s1(width, height), s1W(width, height);
      cpu_ref::peakRatioMargin(sum, std::as_const(best).view(), margin.view(), s1.view());
      cpu_ref::peakRatioMargin(windowedSum, std::as_const(best).view(), marginW.view(), s1W.view());
      Image<std::int16_t> right(width, height), rightW(width, height);
      cpu_ref::rightDisparityIndex(sum, minDisparity, right.view());
      cpu_ref::rightDisparityIndex(windowedSum, minDisparity, rightW.view());
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          ASSERT_EQ(marginW(x, y), margin(x, y));
          ASSERT_EQ(s1W(x, y), s1(x, y));
          ASSERT_EQ(rightW(x, y), right(x, y));
        }
      }
    }
  }
}

// Eq. 1 written on full-range arrays with +infinity outside each window: an independent oracle of
// the windowed recurrence.
std::vector<int> bruteForceSum(const MatchingCostVolume& cost, const SearchWindows& w, int P1, int P2, int paths) {
  const int width = cost.width(), height = cost.height(), D = cost.numDisparities();
  constexpr int kInfinity = 1 << 24;
  const int dirs[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  const auto index = [&](int x, int y, int d) { return (static_cast<std::size_t>(y) * width + x) * D + d; };
  std::vector<int> sum(cost.size(), 0);
  std::vector<int> L(cost.size());
  for (int r = 0; r < paths; ++r) {
    const int dx = dirs[r][0], dy = dirs[r][1];
    for (int i = 0; i < height; ++i) {
      const int y = dy >= 0 ? i : height - 1 - i;
      for (int j = 0; j < width; ++j) {
        const int x = dx >= 0 ? j : width - 1 - j;
        const int px = x - dx, py = y - dy;
        const bool start = px < 0 || px >= width || py < 0 || py >= height;
        int M = kInfinity;
        if (!start) {
          for (int k = 0; k < D; ++k) M = std::min(M, L[index(px, py, k)]);
        }
        for (int d = 0; d < D; ++d) {
          if (!w.contains(x, y, d)) {
            L[index(x, y, d)] = kInfinity;
            continue;
          }
          if (start) {
            L[index(x, y, d)] = cost(x, y, d);
            continue;
          }
          int best = std::min(L[index(px, py, d)], M + P2);
          if (d > 0) best = std::min(best, L[index(px, py, d - 1)] + P1);
          if (d + 1 < D) best = std::min(best, L[index(px, py, d + 1)] + P1);
          L[index(x, y, d)] = cost(x, y, d) + best - M;
        }
      }
    }
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = std::min(kInfinity, sum[i] + L[i]);
  }
  return sum;
}

TEST(GatedStages, RandomWindowsMatchABruteForceOracle) {
  const int width = 29, height = 17, D = 64, minDisparity = 2;
  const MatchingCostVolume cost = randomCost(width, height, D, 5);
  const SearchWindows windows = randomWindows(width, height, D, 9);
  WindowedMatchingCost windowed;
  windowed.resize(windows);
  cpu_ref::restrictToWindows(cost, windowed);
  for (const int paths : {4, 8}) {
    SCOPED_TRACE(paths);
    WindowedAggregatedCost sum;
    cpu_ref::aggregatePaths(windowed, 10, 100, paths, sum);
    const std::vector<int> oracle = bruteForceSum(cost, windows, 10, 100, paths);
    Image<std::int16_t> d16(width, height), best(width, height);
    cpu_ref::selectDisparity(sum, minDisparity, 0, true, {d16.view(), best.view()});
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const Window win = windowAt(windows, x, y);
        int oracleBest = -1;
        for (int d = 0; d < D; ++d) {
          const int expected = oracle[(static_cast<std::size_t>(y) * width + x) * D + d];
          if (!windows.contains(x, y, d)) continue;
          ASSERT_EQ(sum(x, y, d), expected) << x << "," << y << "," << d;
          if (oracleBest < 0 || expected < oracle[(static_cast<std::size_t>(y) * width + x) * D + oracleBest]) {
            oracleBest = d;
          }
        }
        // The winner is the window's first minimum, inside the window.
        ASSERT_EQ(best(x, y), oracleBest);
        ASSERT_GE(best(x, y), win.first);
        ASSERT_LT(best(x, y), win.first + win.count);
      }
    }
    // The right view reads only entries inside windows.
    Image<std::int16_t> right(width, height);
    cpu_ref::rightDisparityIndex(sum, minDisparity, right.view());
    for (int y = 0; y < height; ++y) {
      for (int xr = 0; xr < width; ++xr) {
        int expected = -1;
        int expectedCost = 0;
        for (int d = 0; d < D; ++d) {
          const int x = xr + minDisparity + d;
          if (x < 0 || x >= width || !windows.contains(x, y, d)) continue;
          const int c = oracle[(static_cast<std::size_t>(y) * width + x) * D + d];
          if (expected < 0 || c < expectedCost) {
            expected = d;
            expectedCost = c;
          }
        }
        ASSERT_EQ(right(xr, y), expected) << xr << "," << y;
      }
    }
  }
}

// LiDAR beams: every point of every `rowStep`-th row, exact.
LidarPoints beams(const Image<float>& gt, int rowStep) {
  std::vector<LidarSample> samples;
  for (int y = 1; y < gt.height(); y += rowStep) {
    for (int x = 0; x < gt.width(); ++x) {
      samples.push_back({x, y, static_cast<int>(std::lround(gt(x, y) * kDisparityScale))});
    }
  }
  return LidarPoints(gt.width(), gt.height(), samples);
}

Image<std::int16_t> match(const Parameters& p, const test::SyntheticStereo& s, const LidarPoints* lidar,
                          bool stereo, Image<std::uint8_t>* confidence = nullptr) {
  auto matcher = Matcher::create(Backend::CpuRef, p);
  Image<std::int16_t> out(s.left.width(), s.left.height());
  if (stereo) {
    matcher->compute(s.left.view(), s.right.view(), lidar, out.view());
  } else {
    matcher->compute(GrayImageView(), GrayImageView(), lidar, out.view());
  }
  if (confidence != nullptr) {
    const ImageView<const std::uint8_t> c = matcher->confidence();
    *confidence = Image<std::uint8_t>(c.width, c.height);
    for (int y = 0; y < c.height; ++y) {
      for (int x = 0; x < c.width; ++x) (*confidence)(x, y) = c(x, y);
    }
  }
  return out;
}

bool identical(const Image<std::int16_t>& a, const Image<std::int16_t>& b) {
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      if (a(x, y) != b(x, y)) return false;
    }
  }
  return true;
}

TEST(GatedSearch, WindowsAsWideAsTheRangeGiveTheUngatedFrameBitForBit) {
  const test::SyntheticStereo s = test::makeStereo(97, 41, [](double x, double y) { return 9.0 + 0.06 * x + 0.04 * y; });
  const LidarPoints lidar = beams(s.disparity, 4);
  Parameters p;
  p.numDisparities = 32;
  p.lrCheckWithLidar = true;  // the check too, on the windows
  p.gatedSearch = false;
  const Parameters ungated = p;
  p.gatedSearch = true;
  p.gatedSearchMargin = 512;
  for (const float scale : {1.0f, 0.5f}) {
    {
      const bool stereo = true;  // LiDAR-only frames are never gated (LidarOnlyFramesSearchTheWholeRange)
      SCOPED_TRACE(std::string("fused") + (scale == 1.0f ? "" : ", half scale"));
      Parameters gated = p;
      Parameters plain = ungated;
      gated.scale = plain.scale = scale;
      Image<std::uint8_t> confidence, confidenceGated;
      const Image<std::int16_t> off = match(plain, s, &lidar, stereo, &confidence);
      const Image<std::int16_t> on = match(gated, s, &lidar, stereo, &confidenceGated);
      EXPECT_TRUE(identical(on, off));
      for (int y = 0; y < s.left.height(); ++y) {
        for (int x = 0; x < s.left.width(); ++x) ASSERT_EQ(confidenceGated(x, y), confidence(x, y));
      }
    }
  }
  // Stereo-only frames are never gated, whatever the margin.
  p.gatedSearchMargin = 0;
  EXPECT_TRUE(identical(match(p, s, nullptr, true), match(ungated, s, nullptr, true)));
}

double shareWithinOnePixel(const Image<std::int16_t>& estimate, const Image<float>& gt, int firstColumn) {
  long scored = 0, good = 0;
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = firstColumn; x < gt.width(); ++x) {
      ++scored;
      const int e = estimate(x, y);
      if (e != kInvalidDisparity && std::abs(e / static_cast<double>(kDisparityScale) - gt(x, y)) <= 1.0) ++good;
    }
  }
  return static_cast<double>(good) / static_cast<double>(scored);
}

TEST(GatedSearch, TheGateAloneResolvesAPeriodicTexture) {
  // The texture repeats every 24 px: stereo sees d, d +- 24 alike. With alpha 0 the LiDAR adds no
  // cost, so only the gate (windows 16 wide around the beams' disparities) can pick the right one.
  const test::SyntheticStereo s = test::makeStereo(
      181, 60, [](double x, double) { return 28.0 + 0.04 * x; }, /*period=*/24);
  const LidarPoints lidar = beams(s.disparity, 5);
  Parameters p;
  p.numDisparities = 64;
  p.alpha = 0.0f;
  p.gatedSearch = true;
  p.gatedSearchMargin = 2;
  p.gatedSearchRows = 3;
  const double gated = shareWithinOnePixel(match(p, s, &lidar, true), s.disparity, 40);
  EXPECT_GT(gated, 0.99);
}

TEST(GatedSearch, KeepsBothSidesOfADepthEdgeBetweenBeams) {
  // A near band (40 px) across a far plane (12 px): rows between two beams on either side of the
  // edge see both disparities in their neighbourhood, so their windows hold both.
  const auto disparity = [](double, double y) -> double { return y >= 20 && y < 33 ? 40.0 : 12.0; };
  const test::SyntheticStereo s = test::makeStereo(173, 53, disparity);
  const LidarPoints lidar = beams(s.disparity, 6);
  Parameters p;
  p.numDisparities = 64;
  p.gatedSearch = false;
  const Image<std::int16_t> ungated = match(p, s, &lidar, true);
  p.gatedSearch = true;
  p.gatedSearchMargin = 2;
  p.gatedSearchRows = 6;
  const Image<std::int16_t> gated = match(p, s, &lidar, true);
  const double gatedShare = shareWithinOnePixel(gated, s.disparity, 48);
  EXPECT_GT(gatedShare, 0.97);
  EXPECT_GE(gatedShare, shareWithinOnePixel(ungated, s.disparity, 48) - 0.005);
}

TEST(GatedSearch, IsTheDefaultOfFusedFramesOnly) {
  // Windows as narrow as they get (margin 0, the points' own rows): a fused frame changes with
  // them, a LiDAR-only frame keeps the whole range (its cost is the LiDAR's own: the gate measured
  // worse there, docs/RESULTS.md).
  const test::SyntheticStereo s = test::makeStereo(97, 41, [](double x, double y) { return 9.0 + 0.06 * x + 0.04 * y; });
  const LidarPoints lidar = beams(s.disparity, 4);
  Parameters gated;
  EXPECT_TRUE(gated.gatedSearch);
  gated.numDisparities = 32;
  gated.gatedSearchMargin = 0;
  gated.gatedSearchRows = 0;
  Parameters whole = gated;
  whole.gatedSearch = false;
  EXPECT_FALSE(identical(match(gated, s, &lidar, true), match(whole, s, &lidar, true)));
  EXPECT_TRUE(identical(match(gated, s, &lidar, false), match(whole, s, &lidar, false)));
}

TEST(GatedSearch, EveryBackendTakesTheOption) {
  // cpu_ref, cpu and cuda implement it (tests/backends/test_backends.cpp runs each against cpu_ref,
  // the Gated* cases); a backend without it would refuse the option, never fall back silently
  // (core/matcher.cpp).
  Parameters p;
  p.gatedSearch = true;
  int tested = 0;
  for (const Backend b : {Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
    if (!isAvailable(b)) continue;
    ++tested;
    EXPECT_NO_THROW(Matcher::create(b, p)) << toString(b);
    Parameters whole = p;
    whole.gatedSearch = false;
    auto matcher = Matcher::create(b, whole);
    EXPECT_NO_THROW(matcher->setParameters(p)) << toString(b);
  }
  EXPECT_GE(tested, 1);
}

}  // namespace
}  // namespace lidar_sgm
