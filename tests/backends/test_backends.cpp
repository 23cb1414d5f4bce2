// Every fast backend against cpu_ref (the specification), stage by stage and end to end, bit for
// bit: odd sizes, padded strides, 8- and 16-bit images, 16..256 disparities, non-zero
// minDisparity, 4 and 8 paths, every mode (Triple-SGM included), every option, 1, 2 and 7
// threads. A backend that is not built (or has no device) skips.
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <random>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "backend_test_scenes.hpp"
#include "backends/common/lidar_search_windows.hpp"
#include "backends/common/lidar_weights.hpp"
#include "backends/common/stages.hpp"
#include "lidar_sgm/core/matcher.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef LIDAR_SGM_TEST_CPU_BACKEND
#include "backends/cpu/cpu_stages.hpp"
#endif
#ifdef LIDAR_SGM_TEST_CUDA_BACKEND
#include "backends/cuda/cuda_stages.hpp"
#endif

namespace lidar_sgm {
namespace {

using test::BackendScene;
using test::makeBackendScene;

// A backend's whole-volume stages, with cpu_ref's signatures plus the thread count.
struct StageSet {
  std::function<void(ImageView<const std::uint8_t>, CensusType, ImageView<std::uint64_t>)> census8;
  std::function<void(ImageView<const std::uint16_t>, CensusType, ImageView<std::uint64_t>)> census16;
  std::function<void(ImageView<const std::uint64_t>, ImageView<const std::uint64_t>, CensusType, int,
                     MatchingCostVolume&)> censusCost;
  std::function<void(ImageView<const std::uint64_t>, ImageView<const std::uint64_t>, CensusType, int, int,
                     MatchingCostVolume&)> verticalCensusCost;
  std::function<void(const MatchingCostVolume&, const MatchingCostVolume&, MatchingCostVolume&)> combineCameraCosts;
  std::function<void(const LidarPoints&, const LidarCostTable&, int, MatchingCostVolume&, ImageView<std::uint8_t>)>
      lidarCost;
  std::function<void(const LidarPoints&, int, ImageView<std::uint8_t>)> lidarCoverage;
  std::function<void(const LidarPoints&, int, int, int, int, SearchWindows&)> lidarSearchWindows;
  std::function<void(const MatchingCostVolume&, const MatchingCostVolume&, ImageView<const std::uint8_t>, int, bool,
                     MatchingCostVolume&)> fuseCosts;
  std::function<void(const MatchingCostVolume&, const MatchingCostVolume&, ImageView<const std::uint8_t>,
                     ImageView<const std::uint16_t>, bool, MatchingCostVolume&)> fuseCostsPerPixel;
  std::function<void(const MatchingCostVolume&, int, int, int, AggregatedCostVolume&)> aggregatePaths;
  std::function<void(const AggregatedCostVolume&, int, int, bool, SelectedDisparity)> selectDisparity;
  std::function<void(const AggregatedCostVolume&, int, ImageView<std::int16_t>)> rightDisparityIndex;
  std::function<void(SelectedDisparity, ImageView<const std::int16_t>, ImageView<const std::uint8_t>, int, int, bool)>
      leftRightCheck;
  std::function<void(ImageView<const std::int16_t>, int, ImageView<std::int16_t>)> medianFilter;
  std::function<void(const AggregatedCostVolume&, ImageView<const std::int16_t>, ImageView<std::uint8_t>,
                     ImageView<std::uint16_t>)>
      peakRatioMargin;
  std::function<void(ImageView<const std::int16_t>, ImageView<const std::int16_t>, int, ImageView<std::uint8_t>)>
      leftRightDifference;
};

// The stage entry points of `backend` at `threads`; false when this build has none.
bool stagesOf(const std::string& backend, int threads, StageSet& s) {
#ifdef LIDAR_SGM_TEST_CPU_BACKEND
  if (backend == "cpu") {
    const int t = threads;
    s.census8 = [t](auto image, auto type, auto out) { cpu::censusTransform(image, type, out, t); };
    s.census16 = [t](auto image, auto type, auto out) { cpu::censusTransform(image, type, out, t); };
    s.censusCost = [t](auto l, auto r, auto type, int minD, auto& cost) { cpu::censusCost(l, r, type, minD, cost, t); };
    s.verticalCensusCost = [t](auto l, auto u, auto type, int ratio, int minD, auto& cost) {
      cpu::verticalCensusCost(l, u, type, ratio, minD, cost, t);
    };
    s.combineCameraCosts = [t](const auto& h, const auto& v, auto& c) { cpu::combineCameraCosts(h, v, c, t); };
    s.lidarCost = [t](const auto& p, const auto& table, int minD, auto& cost, auto support) {
      cpu::lidarCost(p, table, minD, cost, support, t);
    };
    s.lidarCoverage = [t](const auto& p, int rows, auto out) { cpu::lidarCoverage(p, rows, out, t); };
    s.lidarSearchWindows = [t](const auto& p, int minD, int D, int rows, int margin, auto& windows) {
      cpu::lidarSearchWindows(p, minD, D, rows, margin, windows, t);
    };
    s.fuseCosts = [t](const auto& l, const auto& st, auto support, int w, bool flag, auto& out) {
      cpu::fuseCosts(l, st, support, w, flag, out, t);
    };
    s.fuseCostsPerPixel = [t](const auto& l, const auto& st, auto support, auto weights, bool flag, auto& out) {
      cpu::fuseCosts(l, st, support, weights, flag, out, t);
    };
    s.aggregatePaths = [t](const auto& cost, int P1, int P2, int paths, auto& sum) {
      cpu::aggregatePaths(cost, P1, P2, paths, sum, t);
    };
    s.selectDisparity = [t](const auto& sum, int minD, int u, bool sub, auto out) {
      cpu::selectDisparity(sum, minD, u, sub, out, t);
    };
    s.rightDisparityIndex = [t](const auto& sum, int minD, auto out) { cpu::rightDisparityIndex(sum, minD, out, t); };
    s.leftRightCheck = [t](auto sel, auto right, auto support, int minD, int maxDiff, bool keep) {
      cpu::leftRightCheck(sel, right, support, minD, maxDiff, keep, t);
    };
    s.medianFilter = [t](auto in, int size, auto out) { cpu::medianFilter(in, size, out, t); };
    s.peakRatioMargin = [t](const auto& sum, auto best, auto out, auto cost) {
      cpu::peakRatioMargin(sum, best, out, cost, t);
    };
    s.leftRightDifference = [t](auto best, auto right, int minD, auto out) {
      cpu::leftRightDifference(best, right, minD, out, t);
    };
    return true;
  }
#endif
#ifdef LIDAR_SGM_TEST_CUDA_BACKEND
  if (backend == "cuda") {
    // The GPU has no thread count: every `threads` runs the same kernels.
    s.census8 = [](auto image, auto type, auto out) { cuda::censusTransform(image, type, out); };
    s.census16 = [](auto image, auto type, auto out) { cuda::censusTransform(image, type, out); };
    s.censusCost = [](auto l, auto r, auto type, int minD, auto& cost) { cuda::censusCost(l, r, type, minD, cost); };
    s.verticalCensusCost = [](auto l, auto u, auto type, int ratio, int minD, auto& cost) {
      cuda::verticalCensusCost(l, u, type, ratio, minD, cost);
    };
    s.combineCameraCosts = [](const auto& h, const auto& v, auto& c) { cuda::combineCameraCosts(h, v, c); };
    s.lidarCost = [](const auto& p, const auto& table, int minD, auto& cost, auto support) {
      cuda::lidarCost(p, table, minD, cost, support);
    };
    s.lidarCoverage = [](const auto& p, int rows, auto out) { cuda::lidarCoverage(p, rows, out); };
    s.lidarSearchWindows = [](const auto& p, int minD, int D, int rows, int margin, auto& windows) {
      cuda::lidarSearchWindows(p, minD, D, rows, margin, windows);
    };
    s.fuseCosts = [](const auto& l, const auto& st, auto support, int w, bool flag, auto& out) {
      cuda::fuseCosts(l, st, support, w, flag, out);
    };
    s.fuseCostsPerPixel = [](const auto& l, const auto& st, auto support, auto weights, bool flag, auto& out) {
      cuda::fuseCosts(l, st, support, weights, flag, out);
    };
    s.aggregatePaths = [](const auto& cost, int P1, int P2, int paths, auto& sum) {
      cuda::aggregatePaths(cost, P1, P2, paths, sum);
    };
    s.selectDisparity = [](const auto& sum, int minD, int u, bool sub, auto out) {
      cuda::selectDisparity(sum, minD, u, sub, out);
    };
    s.rightDisparityIndex = [](const auto& sum, int minD, auto out) { cuda::rightDisparityIndex(sum, minD, out); };
    s.leftRightCheck = [](auto sel, auto right, auto support, int minD, int maxDiff, bool keep) {
      cuda::leftRightCheck(sel, right, support, minD, maxDiff, keep);
    };
    s.medianFilter = [](auto in, int size, auto out) { cuda::medianFilter(in, size, out); };
    s.peakRatioMargin = [](const auto& sum, auto best, auto out, auto cost) {
      cuda::peakRatioMargin(sum, best, out, cost);
    };
    s.leftRightDifference = [](auto best, auto right, int minD, auto out) {
      cuda::leftRightDifference(best, right, minD, out);
    };
    return true;
  }
#endif
  (void)backend;
  (void)threads;
  (void)s;
  return false;
}

template <typename T>
::testing::AssertionResult sameImages(const Image<T>& expected, const Image<T>& actual) {
  for (int y = 0; y < expected.height(); ++y) {
    for (int x = 0; x < expected.width(); ++x) {
      if (expected(x, y) != actual(x, y)) {
        return ::testing::AssertionFailure() << "first difference at (" << x << ", " << y << "): cpu_ref "
                                             << +expected(x, y) << ", backend " << +actual(x, y);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

template <typename T>
::testing::AssertionResult sameVolumes(const CostVolume<T>& expected, const CostVolume<T>& actual) {
  for (int y = 0; y < expected.height(); ++y) {
    for (int x = 0; x < expected.width(); ++x) {
      for (int d = 0; d < expected.numDisparities(); ++d) {
        if (expected(x, y, d) != actual(x, y, d)) {
          return ::testing::AssertionFailure() << "first difference at (" << x << ", " << y << ", d " << d
                                               << "): cpu_ref " << +expected(x, y, d) << ", backend "
                                               << +actual(x, y, d);
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// Stage by stage: (backend, threads).

class BackendStages : public ::testing::TestWithParam<std::tuple<std::string, int>> {
 protected:
  void SetUp() override {
    const std::string& name = std::get<0>(GetParam());
    if (!isAvailable(backendFromString(name))) {
      GTEST_SKIP() << "backend " << name << ": " << unavailableReason(backendFromString(name));
    }
    if (!stagesOf(name, std::get<1>(GetParam()), stages_)) GTEST_SKIP() << name << " has no stage entry points";
  }
  StageSet stages_;
};

struct StageCase {
  int width, height, minDisparity, numDisparities;
};
constexpr StageCase kStageCases[] = {{17, 9, 0, 16}, {64, 40, -8, 32}, {131, 47, 5, 64}};

TEST_P(BackendStages, CensusTransformEightAndSixteenBitPaddedRows) {
  for (const StageCase& c : kStageCases) {
    const BackendScene scene = makeBackendScene(c.width, c.height, c.minDisparity, c.numDisparities, 3);
    for (CensusType type : {CensusType::Census9x7, CensusType::CenterSymmetric9x7}) {
      Image<std::uint64_t> expected(c.width, c.height), actual(c.width, c.height);
      cpu_ref::censusTransform(scene.left8.view(), type, expected.view());
      stages_.census8(scene.left8.view(), type, actual.view());
      EXPECT_TRUE(sameImages(expected, actual)) << c.width << "x" << c.height << " 8-bit " << toString(type);
      cpu_ref::censusTransform(scene.left16.view(), type, expected.view());
      stages_.census16(scene.left16.view(), type, actual.view());
      EXPECT_TRUE(sameImages(expected, actual)) << c.width << "x" << c.height << " 16-bit " << toString(type);
    }
  }
}

TEST_P(BackendStages, CensusAndVerticalCostsAndTheirCombination) {
  for (const StageCase& c : kStageCases) {
    const BackendScene scene = makeBackendScene(c.width, c.height, c.minDisparity, c.numDisparities, 4);
    for (CensusType type : {CensusType::Census9x7, CensusType::CenterSymmetric9x7}) {
      Image<std::uint64_t> left(c.width, c.height), right(c.width, c.height), up(c.width, c.height);
      cpu_ref::censusTransform(scene.left8.view(), type, left.view());
      cpu_ref::censusTransform(scene.right8.view(), type, right.view());
      cpu_ref::censusTransform(scene.up8.view(), type, up.view());
      const auto cl = std::as_const(left).view();
      const auto cr = std::as_const(right).view();
      const auto cu = std::as_const(up).view();
      MatchingCostVolume expected(c.width, c.height, c.numDisparities), actual(c.width, c.height, c.numDisparities);
      cpu_ref::censusCost(cl, cr, type, c.minDisparity, expected);
      stages_.censusCost(cl, cr, type, c.minDisparity, actual);
      EXPECT_TRUE(sameVolumes(expected, actual)) << "censusCost " << c.width << "x" << c.height;
      MatchingCostVolume vExpected(c.width, c.height, c.numDisparities), vActual(c.width, c.height, c.numDisparities);
      const int ratio16 = baselineRatio16(scene.upRatio);
      cpu_ref::verticalCensusCost(cl, cu, type, ratio16, c.minDisparity, vExpected);
      stages_.verticalCensusCost(cl, cu, type, ratio16, c.minDisparity, vActual);
      EXPECT_TRUE(sameVolumes(vExpected, vActual)) << "verticalCensusCost " << c.width << "x" << c.height;
      MatchingCostVolume combinedExpected(c.width, c.height, c.numDisparities);
      MatchingCostVolume combinedActual(c.width, c.height, c.numDisparities);
      cpu_ref::combineCameraCosts(expected, vExpected, combinedExpected);
      stages_.combineCameraCosts(expected, vExpected, combinedActual);
      EXPECT_TRUE(sameVolumes(combinedExpected, combinedActual)) << "combineCameraCosts";
    }
  }
}

TEST_P(BackendStages, LidarCostSupportCoverageAndFusion) {
  for (const StageCase& c : kStageCases) {
    const BackendScene scene = makeBackendScene(c.width, c.height, c.minDisparity, c.numDisparities, 5);
    // 3.95 and 7.9 at cap 255: a point's costs span exactly 17 and 33 disparities, one more than
    // a whole number of 16-byte vectors.
    for (const auto& [sigma, cap] :
         {std::pair<float, int>{2.0f, 62}, {0.7f, 255}, {9.5f, 40}, {3.95f, 255}, {7.9f, 255}}) {
      const LidarCostTable table(sigma, cap);
      MatchingCostVolume expected(c.width, c.height, c.numDisparities), actual(c.width, c.height, c.numDisparities);
      Image<std::uint8_t> supportExpected(c.width, c.height), supportActual(c.width, c.height);
      cpu_ref::lidarCost(scene.lidar, table, c.minDisparity, expected, supportExpected.view());
      stages_.lidarCost(scene.lidar, table, c.minDisparity, actual, supportActual.view());
      EXPECT_TRUE(sameVolumes(expected, actual)) << "lidarCost sigma " << sigma << " cap " << cap;
      EXPECT_TRUE(sameImages(supportExpected, supportActual)) << "support";

      Image<std::uint64_t> left(c.width, c.height), right(c.width, c.height);
      cpu_ref::censusTransform(scene.left8.view(), CensusType::Census9x7, left.view());
      cpu_ref::censusTransform(scene.right8.view(), CensusType::Census9x7, right.view());
      MatchingCostVolume stereo(c.width, c.height, c.numDisparities);
      cpu_ref::censusCost(std::as_const(left).view(), std::as_const(right).view(), CensusType::Census9x7,
                          c.minDisparity, stereo);
      for (const int w : {0, 1, 179, 255, 256}) {
        for (const bool stereoWithoutLidar : {false, true}) {
          MatchingCostVolume fusedExpected(c.width, c.height, c.numDisparities);
          MatchingCostVolume fusedActual(c.width, c.height, c.numDisparities);
          cpu_ref::fuseCosts(expected, stereo, std::as_const(supportExpected).view(), w, stereoWithoutLidar,
                             fusedExpected);
          stages_.fuseCosts(expected, stereo, std::as_const(supportExpected).view(), w, stereoWithoutLidar,
                            fusedActual);
          EXPECT_TRUE(sameVolumes(fusedExpected, fusedActual)) << "fuseCosts w " << w;
        }
      }
      // Per-pixel weights: every value of [0, 256] at random, and the adaptive weights of the scene.
      Image<std::uint16_t> randomWeights(c.width, c.height), adaptiveWeights(c.width, c.height);
      std::mt19937 engine(13);
      for (int y = 0; y < c.height; ++y) {
        for (int x = 0; x < c.width; ++x) randomWeights(x, y) = static_cast<std::uint16_t>(engine() % 257u);
      }
      Parameters adaptive;
      adaptive.alphaMode = AlphaMode::Adaptive;
      lidarWeights(scene.lidar, adaptive, adaptiveWeights.view());
      for (const Image<std::uint16_t>* weights : {&randomWeights, &adaptiveWeights}) {
        for (const bool stereoWithoutLidar : {false, true}) {
          MatchingCostVolume fusedExpected(c.width, c.height, c.numDisparities);
          MatchingCostVolume fusedActual(c.width, c.height, c.numDisparities);
          cpu_ref::fuseCosts(expected, stereo, std::as_const(supportExpected).view(), weights->view(),
                             stereoWithoutLidar, fusedExpected);
          stages_.fuseCostsPerPixel(expected, stereo, std::as_const(supportExpected).view(), weights->view(),
                                    stereoWithoutLidar, fusedActual);
          EXPECT_TRUE(sameVolumes(fusedExpected, fusedActual))
              << "fuseCosts per pixel, " << (weights == &randomWeights ? "random" : "adaptive") << " weights";
        }
      }
    }
    for (const int rows : {1, 6, 64}) {
      Image<std::uint8_t> coverageExpected(c.width, c.height), coverageActual(c.width, c.height);
      cpu_ref::lidarCoverage(scene.lidar, rows, coverageExpected.view());
      stages_.lidarCoverage(scene.lidar, rows, coverageActual.view());
      EXPECT_TRUE(sameImages(coverageExpected, coverageActual)) << "lidarCoverage rows " << rows;
    }
    // The gate's windows (lidarSearchWindows, the host's single-threaded passes, is the rule).
    struct Gate {
      int rows, margin;
    };
    for (const Gate& g : {Gate{1, 0}, Gate{6, 12}, Gate{64, 3}}) {
      SearchWindows expected, actual;
      lidarSearchWindows(scene.lidar, c.minDisparity, c.numDisparities, g.rows, g.margin, expected);
      stages_.lidarSearchWindows(scene.lidar, c.minDisparity, c.numDisparities, g.rows, g.margin, actual);
      ASSERT_EQ(actual.width(), c.width);
      ASSERT_EQ(actual.height(), c.height);
      int differences = 0;
      for (int y = 0; y < c.height; ++y) {
        for (int x = 0; x < c.width; ++x) {
          if (expected.first(x, y) != actual.first(x, y) || expected.count(x, y) != actual.count(x, y)) ++differences;
        }
      }
      EXPECT_EQ(differences, 0) << "lidarSearchWindows rows " << g.rows << " margin " << g.margin;
    }
  }
}

// The gate's windows at the ends of the rule (search_window_rule.hpp): points outside the range
// on either side, x16 values at and beyond 16 bits (clamped), negative and odd range starts, the
// smallest and largest ranges and margins, pixels with no point and rows with none.
TEST_P(BackendStages, LidarSearchWindowsAtTheRulesEnds) {
  struct Gate {
    int width, height, minDisparity, numDisparities, rows, margin;
  };
  const Gate gates[] = {{37, 11, 0, 16, 1, 0},     {70, 23, -16, 48, 3, 5},   {129, 19, 7, 512, 2, 512},
                        {33, 9, -256, 512, 0, 1},  {100, 30, 13, 64, 6, 12}};
  std::mt19937 engine(29);
  for (const Gate& g : gates) {
    // x16 disparities (a point's is positive) from below the range to beyond the 16 bits the rule
    // keeps.
    std::uniform_int_distribution<int> wide(1, 40000);
    const int low = std::max(1, g.minDisparity * 16 - 200);
    std::uniform_int_distribution<int> inside(low, std::max(low + 400, (g.minDisparity + g.numDisparities) * 16 + 200));
    std::uniform_int_distribution<int> column(0, g.width - 1);
    std::uniform_int_distribution<int> row(0, g.height - 1);
    std::vector<LidarSample> samples;
    for (int i = 0; i < g.width * g.height / 6; ++i) {
      const int y = row(engine);
      if (y % 5 == 2) continue;  // rows without points
      const int pick = static_cast<int>(engine() % 8);
      const int value = pick == 0 ? wide(engine) : pick == 1 ? 32767 + static_cast<int>(engine() % 3) : inside(engine);
      samples.push_back({column(engine), y, value});
    }
    LidarPoints points;
    points.assign(g.width, g.height, samples);
    SearchWindows expected, actual;
    lidarSearchWindows(points, g.minDisparity, g.numDisparities, g.rows, g.margin, expected);
    stages_.lidarSearchWindows(points, g.minDisparity, g.numDisparities, g.rows, g.margin, actual);
    int differences = 0;
    int narrowed = 0;
    for (int y = 0; y < g.height; ++y) {
      for (int x = 0; x < g.width; ++x) {
        if (expected.first(x, y) != actual.first(x, y) || expected.count(x, y) != actual.count(x, y)) ++differences;
        narrowed += expected.count(x, y) < g.numDisparities ? 1 : 0;
      }
    }
    EXPECT_EQ(differences, 0) << g.width << "x" << g.height << " range " << g.minDisparity << "+" << g.numDisparities
                              << " rows " << g.rows << " margin " << g.margin;
    if (g.numDisparities > 16 && g.margin < 512) {
      EXPECT_GT(narrowed, 0) << "no window narrowed: the case tests nothing";
    }
  }
}

// A cost volume with every value of [0, maxCost], random, as the aggregation's input.
MatchingCostVolume randomCosts(int width, int height, int D, int maxCost, unsigned seed) {
  MatchingCostVolume cost(width, height, D);
  std::mt19937 engine(seed);
  for (std::size_t i = 0; i < cost.size(); ++i) {
    cost.data()[i] = static_cast<std::uint8_t>(engine() % static_cast<unsigned>(maxCost + 1));
  }
  return cost;
}

TEST_P(BackendStages, AggregatePathsSelectionAndLeftRightCheck) {
  struct Penalties {
    int P1, P2, maxCost;
  };
  for (const StageCase& c : kStageCases) {
    // 62 + 192 and 62 + 193: the largest path cost one below and at 255, where the backends'
    // 8-bit path costs end (the cuda backend's 8-bit volumes keep 255 for an absent entry).
    for (const Penalties& pen : {Penalties{10, 100, 62}, Penalties{0, 1, 62}, Penalties{3999, 4000, 255},
                                 Penalties{10, 192, 62}, Penalties{10, 193, 62}}) {
      const MatchingCostVolume cost = randomCosts(c.width, c.height, c.numDisparities, pen.maxCost, 11);
      for (const int paths : {4, 8}) {
        AggregatedCostVolume expected, actual;
        cpu_ref::aggregatePaths(cost, pen.P1, pen.P2, paths, expected);
        stages_.aggregatePaths(cost, pen.P1, pen.P2, paths, actual);
        ASSERT_TRUE(sameVolumes(expected, actual)) << "aggregatePaths P1 " << pen.P1 << " P2 " << pen.P2 << " paths "
                                                   << paths << " " << c.width << "x" << c.height;
        for (const int uniqueness : {0, 5, 50}) {
          for (const bool subpixel : {true, false}) {
            Image<std::int16_t> dispExpected(c.width, c.height), bestExpected(c.width, c.height);
            Image<std::int16_t> dispActual(c.width, c.height), bestActual(c.width, c.height);
            const SelectedDisparity selExpected{dispExpected.view(), bestExpected.view()};
            const SelectedDisparity selActual{dispActual.view(), bestActual.view()};
            cpu_ref::selectDisparity(expected, c.minDisparity, uniqueness, subpixel, selExpected);
            stages_.selectDisparity(expected, c.minDisparity, uniqueness, subpixel, selActual);
            EXPECT_TRUE(sameImages(dispExpected, dispActual)) << "selectDisparity u " << uniqueness;
            EXPECT_TRUE(sameImages(bestExpected, bestActual)) << "selectDisparity index";

            Image<std::int16_t> rightExpected(c.width, c.height), rightActual(c.width, c.height);
            cpu_ref::rightDisparityIndex(expected, c.minDisparity, rightExpected.view());
            stages_.rightDisparityIndex(expected, c.minDisparity, rightActual.view());
            EXPECT_TRUE(sameImages(rightExpected, rightActual)) << "rightDisparityIndex";
            Image<std::uint8_t> marginExpected(c.width, c.height), marginActual(c.width, c.height);
            Image<std::uint16_t> costExpected(c.width, c.height), costActual(c.width, c.height);
            cpu_ref::peakRatioMargin(expected, std::as_const(bestExpected).view(), marginExpected.view(),
                                     costExpected.view());
            stages_.peakRatioMargin(expected, std::as_const(bestExpected).view(), marginActual.view(),
                                    costActual.view());
            EXPECT_TRUE(sameImages(marginExpected, marginActual)) << "peakRatioMargin u " << uniqueness;
            EXPECT_TRUE(sameImages(costExpected, costActual)) << "peakRatioMargin best cost";
            Image<std::uint8_t> lrExpected(c.width, c.height), lrActual(c.width, c.height);
            cpu_ref::leftRightDifference(std::as_const(bestExpected).view(), std::as_const(rightExpected).view(),
                                         c.minDisparity, lrExpected.view());
            stages_.leftRightDifference(std::as_const(bestExpected).view(), std::as_const(rightExpected).view(),
                                        c.minDisparity, lrActual.view());
            EXPECT_TRUE(sameImages(lrExpected, lrActual)) << "leftRightDifference";
            Image<std::uint8_t> support(c.width, c.height);
            for (int y = 0; y < c.height; ++y) {
              for (int x = 0; x < c.width; ++x) support(x, y) = (x * 7 + y * 3) % 5 == 0 ? 1 : 0;
            }
            for (const bool keep : {false, true}) {
              for (const bool withSupport : {false, true}) {
                Image<std::int16_t> dE = dispExpected, bE = bestExpected, dA = dispExpected, bA = bestExpected;
                const ImageView<const std::uint8_t> sv =
                    withSupport ? std::as_const(support).view() : ImageView<const std::uint8_t>();
                cpu_ref::leftRightCheck({dE.view(), bE.view()}, std::as_const(rightExpected).view(), sv,
                                        c.minDisparity, 1, keep);
                stages_.leftRightCheck({dA.view(), bA.view()}, std::as_const(rightExpected).view(), sv,
                                       c.minDisparity, 1, keep);
                EXPECT_TRUE(sameImages(dE, dA)) << "leftRightCheck keep " << keep << " support " << withSupport;
                EXPECT_TRUE(sameImages(bE, bA)) << "leftRightCheck index";
              }
            }
          }
        }
      }
    }
  }
}

TEST_P(BackendStages, MedianFilterWithInvalidPixels) {
  // The stage cases, and images of 1 to 4 rows, where every 5x5 window is cut by the image's top
  // or bottom (windows of 1 to 4 rows).
  std::vector<StageCase> cases(std::begin(kStageCases), std::end(kStageCases));
  for (const StageCase& c : {StageCase{64, 1, 0, 16}, StageCase{64, 2, 0, 16}, StageCase{41, 3, 0, 16},
                             StageCase{70, 4, 0, 16}}) {
    cases.push_back(c);
  }
  for (const StageCase& c : cases) {
    std::mt19937 engine(9);
    for (const int invalidOneIn : {1000000, 40, 3}) {
      Image<std::int16_t> in(c.width, c.height);
      for (int y = 0; y < c.height; ++y) {
        for (int x = 0; x < c.width; ++x) {
          const bool invalid = engine() % static_cast<unsigned>(invalidOneIn) == 0;
          in(x, y) = invalid ? kInvalidDisparity : static_cast<std::int16_t>(engine() % 4096u) - 100;
        }
      }
      const test::PaddedImage<std::int16_t> paddedIn = test::padded(in, 5, std::int16_t{77});
      for (const int size : {0, 3, 5}) {
        Image<std::int16_t> expected(c.width, c.height), actual(c.width, c.height);
        cpu_ref::medianFilter(paddedIn.view(), size, expected.view());
        stages_.medianFilter(paddedIn.view(), size, actual.view());
        EXPECT_TRUE(sameImages(expected, actual)) << "median " << size << " invalid 1/" << invalidOneIn << " "
                                                  << c.width << "x" << c.height;
      }
    }
  }
}

std::string stageName(const ::testing::TestParamInfo<std::tuple<std::string, int>>& info) {
  return std::get<0>(info.param) + "_" + std::to_string(std::get<1>(info.param)) + "threads";
}

INSTANTIATE_TEST_SUITE_P(Backends, BackendStages,
                         ::testing::Combine(::testing::Values("cpu", "cuda"), ::testing::Values(1, 2, 7)), stageName);

// ---------------------------------------------------------------------------------------------
// End to end: Matcher::create(backend) against Matcher::create(cpu_ref) on whole frames.

struct FrameCase {
  std::string name;
  int width, height;
  int bits;           // 8 or 16
  std::string mode;   // "stereo", "lidar", "fused", "triple", "triple_fused"
  std::function<void(Parameters&)> tweak;
};

// ctest lists a case by its name rather than by the bytes of the struct.
void PrintTo(const FrameCase& c, std::ostream* os) { *os << c.name; }

std::vector<FrameCase> frameCases() {
  const auto none = [](Parameters&) {};
  std::vector<FrameCase> cases = {
      {"Fused631x479", 631, 479, 8, "fused", none},
      {"Stereo631x479", 631, 479, 8, "stereo", none},
      {"Lidar631x479", 631, 479, 8, "lidar", none},
      {"Fused17x9", 17, 9, 8, "fused", [](Parameters& p) { p.numDisparities = 16; }},
      // Two threads split the rows into two bands of chunks of 8 (the cpu backend's sweepBands):
      // 16 rows, two whole chunks; 17, a last chunk of one row; 8, no second band.
      {"Fused131x16", 131, 16, 8, "fused", [](Parameters& p) { p.numDisparities = 32; }},
      {"EightPathsStereo131x17", 131, 17, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.paths = 8; }},
      {"Fused131x8", 131, 8, 8, "fused", [](Parameters& p) { p.numDisparities = 32; }},
      {"Stereo17x9", 17, 9, 8, "stereo", [](Parameters& p) { p.numDisparities = 16; }},
      {"Fused16Bit", 131, 61, 16, "fused", [](Parameters& p) { p.numDisparities = 64; }},
      {"Stereo16Bit", 131, 61, 16, "stereo", [](Parameters& p) { p.numDisparities = 64; }},
      {"Disparities16", 97, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 16; }},
      {"Disparities256", 331, 61, 8, "fused", [](Parameters& p) { p.numDisparities = 256; }},
      // 80: whole vectors of the widest target, then a tail of 16 (AVX-512: 64 + 16; AVX2: 2 x 32 + 16).
      {"Disparities80", 131, 61, 8, "fused", [](Parameters& p) { p.numDisparities = 80; }},
      {"MinDisparityNegative", 131, 61, 8, "stereo",
       [](Parameters& p) { p.numDisparities = 64; p.minDisparity = -7; }},
      {"MinDisparityPositive", 131, 61, 8, "fused", [](Parameters& p) { p.numDisparities = 64; p.minDisparity = 9; }},
      {"EightPaths", 131, 61, 8, "fused", [](Parameters& p) { p.numDisparities = 64; p.paths = 8; }},
      {"EightPathsStereo", 131, 61, 8, "stereo", [](Parameters& p) { p.numDisparities = 64; p.paths = 8; }},
      {"LargePenaltiesAndCap", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.P1 = 3000; p.P2 = 4000; p.lidarCostCap = 255; }},
      {"EightPathsLargePenalties", 99, 41, 8, "lidar",
       [](Parameters& p) { p.numDisparities = 32; p.paths = 8; p.P2 = 4000; p.lidarCostCap = 255; }},
      {"ZeroPenalty", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.P1 = 0; p.P2 = 1; }},
      // The largest path cost (62 + P2) at 254 and 255: the last 8-bit frames of the backends.
      {"PathCosts254", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.P2 = 192; }},
      {"PathCosts255", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.P2 = 193; }},
      {"AlphaZero", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.alpha = 0.0f; }},
      {"AlphaOne", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.alpha = 1.0f; }},
      {"SigmaAndCap", 99, 41, 8, "fused",
       [](Parameters& p) { p.numDisparities = 32; p.sigma = 7.3f; p.lidarCostCap = 17; }},
      {"StereoCostWithoutLidar", 99, 41, 8, "fused",
       [](Parameters& p) { p.numDisparities = 32; p.stereoCostWithoutLidar = true; }},
      {"Uniqueness", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.uniquenessRatio = 10; }},
      {"NoLrCheck", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.lrCheck = false; }},
      {"LrCheckWithLidar", 99, 41, 8, "fused",
       [](Parameters& p) { p.numDisparities = 32; p.lrCheckWithLidar = true; p.lidarCoverageRows = 2; }},
      {"Disp12MaxDiff", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.disp12MaxDiff = 4; }},
      {"Median3", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.medianSize = 3; }},
      {"MedianOff", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.medianSize = 0; }},
      {"NoConfidence", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.confidence = false; }},
      {"NoSubpixel", 99, 41, 8, "fused", [](Parameters& p) { p.numDisparities = 32; p.subpixel = false; }},
      {"CenterSymmetricCensus", 99, 41, 8, "stereo",
       [](Parameters& p) { p.numDisparities = 32; p.censusType = CensusType::CenterSymmetric9x7; }},
      {"TripleStereo", 131, 61, 8, "triple", [](Parameters& p) { p.numDisparities = 64; }},
      {"TripleFused16Bit", 131, 61, 16, "triple_fused", [](Parameters& p) { p.numDisparities = 64; }},
      {"HalfScaleFused", 131, 61, 8, "fused", [](Parameters& p) { p.numDisparities = 64; p.scale = 0.5f; }},
      {"AdaptiveAlpha", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.alphaMode = AlphaMode::Adaptive; }},
      {"AdaptiveAlphaOddSize", 97, 41, 8, "fused",
       [](Parameters& p) { p.numDisparities = 32; p.minDisparity = 3; p.alpha = 0.4f; p.alphaMode = AlphaMode::Adaptive; }},
      {"AdaptiveAlphaStereoCostWithoutLidar", 99, 41, 8, "fused",
       [](Parameters& p) { p.numDisparities = 32; p.stereoCostWithoutLidar = true; p.alphaMode = AlphaMode::Adaptive; }},
      {"AdaptiveAlphaTripleFused", 131, 61, 16, "triple_fused",
       [](Parameters& p) { p.numDisparities = 64; p.alphaMode = AlphaMode::Adaptive; }},
      {"AdaptiveAlphaHalfScale", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.scale = 0.5f; p.alphaMode = AlphaMode::Adaptive; }},
      {"HalfScaleStereo16Bit", 133, 63, 16, "stereo",
       [](Parameters& p) { p.numDisparities = 64; p.minDisparity = 4; p.scale = 0.5f; }},
      // The LiDAR-gated search (gated_stages.hpp): windows from the scene's points.
      {"GatedFused631x479", 631, 479, 8, "fused", [](Parameters& p) { p.gatedSearch = true; }},
      {"GatedLidarIsNotGated", 131, 61, 8, "lidar", [](Parameters& p) { p.numDisparities = 64; p.gatedSearch = true; }},
      {"GatedStereoIsNotGated", 99, 41, 8, "stereo", [](Parameters& p) { p.numDisparities = 32; p.gatedSearch = true; }},
      {"GatedNarrowWindows", 97, 41, 8, "fused",
       [](Parameters& p) {
         p.numDisparities = 64; p.minDisparity = 9; p.gatedSearch = true; p.gatedSearchMargin = 0; p.gatedSearchRows = 1;
       }},
      {"GatedEightPaths", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.paths = 8; p.gatedSearch = true; p.gatedSearchMargin = 2; }},
      {"GatedLargePenaltiesAndCap", 131, 61, 8, "fused",
       [](Parameters& p) {
         p.numDisparities = 64; p.P1 = 3000; p.P2 = 4000; p.lidarCostCap = 255; p.gatedSearch = true; p.gatedSearchMargin = 1;
       }},
      {"GatedUniquenessAndLrCheck", 99, 41, 8, "fused",
       [](Parameters& p) {
         p.numDisparities = 32; p.uniquenessRatio = 10; p.lrCheckWithLidar = true; p.lidarCoverageRows = 2;
         p.gatedSearch = true; p.gatedSearchMargin = 3; p.gatedSearchRows = 2;
       }},
      {"GatedTripleFused16Bit", 131, 61, 16, "triple_fused",
       [](Parameters& p) { p.numDisparities = 64; p.gatedSearch = true; p.gatedSearchMargin = 4; }},
      {"GatedHalfScale", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.scale = 0.5f; p.gatedSearch = true; p.gatedSearchMargin = 2; }},
      {"GatedAdaptiveAlpha", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.alphaMode = AlphaMode::Adaptive; p.gatedSearch = true; }},
      {"GatedDefaults", 131, 61, 8, "fused", [](Parameters& p) { p = Parameters(); p.numDisparities = 64; }},
      {"GatedPathCosts254", 131, 61, 8, "fused",
       [](Parameters& p) { p.numDisparities = 64; p.P2 = 192; p.gatedSearch = true; p.gatedSearchMargin = 2; }},
  };
  return cases;
}

class BackendFrames : public ::testing::TestWithParam<std::tuple<std::string, int, FrameCase>> {};

Image<std::uint8_t> copyOf(ImageView<const std::uint8_t> view) {
  Image<std::uint8_t> out(view.width, view.height);
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) out(x, y) = view(x, y);
  }
  return out;
}

// What cpu_ref makes of one frame case. It runs on one thread whatever Parameters::threads says,
// so its outputs are the same for every (backend, threads) of the case: computed at the case's
// first test and kept, instead of once per test (three thread counts, two backends).
struct ReferenceFrame {
  Image<std::int16_t> disparity;
  Image<std::uint8_t> support;
  Image<std::uint8_t> confidence;
  ConfidenceInputs inputs;
  MatchMode mode = MatchMode::Fused;
};

const ReferenceFrame& referenceFrame(const FrameCase& c, const Parameters& params, const GrayImageView& left,
                                     const GrayImageView& right, const VerticalView& up, const LidarPoints* lidar) {
  static std::map<std::string, ReferenceFrame> frames;
  const auto found = frames.find(c.name);
  if (found != frames.end()) return found->second;
  auto reference = Matcher::create(Backend::CpuRef, params);
  ReferenceFrame frame;
  frame.disparity = Image<std::int16_t>(c.width, c.height);
  reference->compute(left, right, up, lidar, frame.disparity.view());
  frame.support = copyOf(reference->lidarSupport());
  if (params.confidence) frame.confidence = copyOf(reference->confidence());
  frame.inputs = reference->confidenceInputs();
  frame.mode = reference->lastMode();
  return frames.emplace(c.name, std::move(frame)).first->second;
}

TEST_P(BackendFrames, MatchesCpuRefBitForBit) {
  const auto& [name, threads, c] = GetParam();
  if (!isAvailable(backendFromString(name))) {
    GTEST_SKIP() << "backend " << name << ": " << unavailableReason(backendFromString(name));
  }
  Parameters params;
  // Every case searches the whole range unless it gates (the Gated* cases): fused frames gate by
  // default, so without this the whole-range kernels would run on stereo and LiDAR-only cases only.
  params.gatedSearch = false;
  c.tweak(params);
  params.threads = threads;
  const BackendScene scene =
      makeBackendScene(c.width, c.height, params.minDisparity, params.numDisparities, 21);
  const bool sixteen = c.bits == 16;
  const GrayImageView left = sixteen ? GrayImageView(scene.left16.view()) : GrayImageView(scene.left8.view());
  const GrayImageView right = c.mode == "lidar" ? GrayImageView()
                              : sixteen        ? GrayImageView(scene.right16.view())
                                               : GrayImageView(scene.right8.view());
  VerticalView up;
  if (c.mode == "triple" || c.mode == "triple_fused") {
    up.up = sixteen ? GrayImageView(scene.up16.view()) : GrayImageView(scene.up8.view());
    up.baselineRatio = scene.upRatio;
  }
  const bool withLidar = c.mode == "lidar" || c.mode == "fused" || c.mode == "triple_fused";
  const LidarPoints* lidar = withLidar ? &scene.lidar : nullptr;
  if (params.gatedSearch && withLidar && params.scale == 1.0f) {
    // The gated cases must narrow the search somewhere, or they would test the whole range only.
    SearchWindows windows;
    lidarSearchWindows(scene.lidar, params.minDisparity, params.numDisparities, params.gatedSearchRows,
                       params.gatedSearchMargin, windows);
    int narrowed = 0;
    for (int y = 0; y < c.height; ++y) {
      for (int x = 0; x < c.width; ++x) narrowed += windows.count(x, y) < params.numDisparities ? 1 : 0;
    }
    EXPECT_GT(narrowed, c.width * c.height / 10) << "pixels with a window narrower than the range";
  }

  const ReferenceFrame& reference = referenceFrame(c, params, left, right, up, lidar);
  const Image<std::int16_t>& expected = reference.disparity;
  std::unique_ptr<Matcher> backend = Matcher::create(backendFromString(name), params);
  ASSERT_EQ(toString(backend->backend()), name);
  Image<std::int16_t> actual(c.width, c.height);
  // Twice: the second frame reuses the buffers of the first and must not depend on them.
  for (int frame = 0; frame < 2; ++frame) {
    actual.fill(123);
    backend->compute(left, right, up, lidar, actual.view());
    ASSERT_TRUE(sameImages(expected, actual)) << c.name << ", frame " << frame;
  }
  EXPECT_EQ(backend->lastMode(), reference.mode);
  EXPECT_TRUE(sameImages(reference.support, copyOf(backend->lidarSupport()))) << "lidarSupport";
  // The confidence (on by default) and the inputs it was computed from.
  if (params.confidence) {
    ASSERT_EQ(backend->confidence().width, c.width);
    EXPECT_TRUE(sameImages(reference.confidence, copyOf(backend->confidence()))) << "confidence";
    EXPECT_TRUE(sameImages(reference.inputs.margin, backend->confidenceInputs().margin)) << "margin";
    EXPECT_TRUE(sameImages(reference.inputs.bestCost, backend->confidenceInputs().bestCost));
    EXPECT_TRUE(sameImages(reference.inputs.leftRightDifference, backend->confidenceInputs().leftRightDifference))
        << "leftRightDifference";
    // The core's inputs: computed by the core for the CPU backends, on the device by cuda.
    EXPECT_TRUE(sameImages(reference.inputs.lidarDistance, backend->confidenceInputs().lidarDistance))
        << "lidarDistance";
    EXPECT_TRUE(sameImages(reference.inputs.texture, backend->confidenceInputs().texture)) << "texture";
    EXPECT_TRUE(sameImages(reference.inputs.saturated, backend->confidenceInputs().saturated)) << "saturated";
    EXPECT_TRUE(sameImages(reference.inputs.disparityRange, backend->confidenceInputs().disparityRange))
        << "disparityRange";
  } else {
    EXPECT_TRUE(backend->confidence().empty());
  }
  // A result that is all invalid would match trivially: the frames must have estimates.
  int valid = 0;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) valid += expected(x, y) != kInvalidDisparity ? 1 : 0;
  }
  EXPECT_GT(valid, c.width * c.height / 3);
}

std::string frameName(const ::testing::TestParamInfo<std::tuple<std::string, int, FrameCase>>& info) {
  return std::get<0>(info.param) + "_" + std::to_string(std::get<1>(info.param)) + "threads_" +
         std::get<2>(info.param).name;
}

INSTANTIATE_TEST_SUITE_P(Backends, BackendFrames,
                         ::testing::Combine(::testing::Values("cpu", "cuda"), ::testing::Values(1, 2, 7),
                                            ::testing::ValuesIn(frameCases())),
                         frameName);

// One matcher through frames of changing size, search range, path count and cost bounds: buffers
// kept from an earlier frame (larger, smaller, another layout) must never leak into a result.
TEST(BackendReuse, OneMatcherThroughChangingFramesMatchesCpuRef) {
  for (const std::string name : {"cpu", "cuda"}) {
    if (!isAvailable(backendFromString(name))) continue;
    std::unique_ptr<Matcher> backend;
    struct Step {
      int width, height, numDisparities, paths, P2, cap;
      bool gated;  // the gated search's sentinels must not outlive its frames, nor be missing after others
    };
    for (const Step& step : {Step{131, 61, 64, 4, 100, 62, false}, Step{97, 41, 32, 8, 100, 62, true},
                             Step{131, 61, 64, 8, 4000, 255, false}, Step{131, 61, 64, 8, 4000, 255, true},
                             Step{64, 40, 16, 4, 100, 62, false}, Step{131, 61, 64, 4, 100, 62, true},
                             Step{131, 61, 64, 4, 100, 62, false}}) {
      Parameters params;
      params.numDisparities = step.numDisparities;
      params.paths = step.paths;
      params.P2 = step.P2;
      params.lidarCostCap = step.cap;
      params.gatedSearch = step.gated;
      params.gatedSearchMargin = 2;
      params.threads = 2;
      if (!backend) {
        backend = Matcher::create(backendFromString(name), params);
      } else {
        backend->setParameters(params);
      }
      const BackendScene scene = makeBackendScene(step.width, step.height, 0, step.numDisparities, 33);
      Image<std::int16_t> expected(step.width, step.height), actual(step.width, step.height);
      Matcher::create(Backend::CpuRef, params)->compute(scene.left8.view(), scene.right8.view(), &scene.lidar,
                                                        expected.view());
      backend->compute(scene.left8.view(), scene.right8.view(), &scene.lidar, actual.view());
      EXPECT_TRUE(sameImages(expected, actual)) << name << " " << step.width << "x" << step.height << " D "
                                                << step.numDisparities << " paths " << step.paths
                                                << (step.gated ? " gated" : "");
    }
  }
}

#ifdef _OPENMP
// With two threads the cpu backend's bands help each other: whichever finishes its costs first
// costs the other band's rows from that band's far end (sweeps.cpp, bandHelp), and the owner only
// steps its paths over them. Which rows are helped depends on timing; with a team of one thread
// (the matcher called inside another parallel region) band 0's thread costs every row of band 1,
// and band 1 only steps: every helped-row path runs, deterministically, and must not change a bit.
TEST(CpuBands, ATeamOfOneCostsTheOtherBandForItAndMatchesCpuRef) {
  if (!isAvailable(Backend::Cpu)) GTEST_SKIP() << unavailableReason(Backend::Cpu);
  const int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);  // the matcher's own region gets one thread
  for (const FrameCase& c : frameCases()) {
    // Costs in place (census, packed or not), and packed after the paths (Triple-SGM, gated).
    if (c.name != "Fused131x16" && c.name != "EightPathsStereo131x17" && c.name != "GatedDefaults" &&
        c.name != "GatedTripleFused16Bit") {
      continue;
    }
    Parameters params;
    params.gatedSearch = false;
    c.tweak(params);
    params.threads = 2;
    const BackendScene scene = makeBackendScene(c.width, c.height, params.minDisparity, params.numDisparities, 21);
    const bool sixteen = c.bits == 16;
    const GrayImageView left = sixteen ? GrayImageView(scene.left16.view()) : GrayImageView(scene.left8.view());
    const GrayImageView right = sixteen ? GrayImageView(scene.right16.view()) : GrayImageView(scene.right8.view());
    VerticalView up;
    if (c.mode == "triple_fused") {
      up.up = sixteen ? GrayImageView(scene.up16.view()) : GrayImageView(scene.up8.view());
      up.baselineRatio = scene.upRatio;
    }
    const LidarPoints* lidar = c.mode == "stereo" ? nullptr : &scene.lidar;
    Image<std::int16_t> expected(c.width, c.height), actual(c.width, c.height);
    Matcher::create(Backend::CpuRef, params)->compute(left, right, up, lidar, expected.view());
    std::unique_ptr<Matcher> cpu = Matcher::create(Backend::Cpu, params);
    int team = 0;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
      {
#pragma omp parallel num_threads(2)
        {
#pragma omp single
          team = omp_get_num_threads();
        }
        cpu->compute(left, right, up, lidar, actual.view());
      }
    }
    EXPECT_EQ(team, 1) << "a nested region of two threads must get one";
    EXPECT_TRUE(sameImages(expected, actual)) << c.name;
  }
  omp_set_max_active_levels(levels);
}
#endif

// Only a GPU backend takes device memory; the others say so instead of reading a bad pointer.
TEST(DeviceFrames, HostBackendsRefuseDeviceMemory) {
  for (const Backend b : {Backend::CpuRef, Backend::Cpu}) {
    if (!isAvailable(b)) continue;
    const BackendScene scene = makeBackendScene(64, 40, 0, 32, 3);
    Parameters params;
    params.numDisparities = 32;
    auto matcher = Matcher::create(b, params);
    DeviceFrame frame;
    frame.left = scene.left8.view();
    frame.right = scene.right8.view();
    Image<std::int16_t> out(64, 40);
    try {
      matcher->computeOnDevice(frame, out.view());
      ADD_FAILURE() << toString(b) << " accepted a device frame";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("cuda"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(toString(b)), std::string::npos) << e.what();
    }
  }
}

TEST(DeviceFrames, BadDeviceFramesAreRefusedBeforeTheBackend) {
  auto matcher = Matcher::create(Backend::CpuRef);
  Image<std::int16_t> out(64, 40);
  Image<std::uint8_t> left(64, 40), right(63, 40);
  DeviceFrame frame;
  EXPECT_THROW(matcher->computeOnDevice(frame, out.view()), std::invalid_argument);  // nothing to match
  frame.left = left.view();
  frame.right = right.view();
  try {
    matcher->computeOnDevice(frame, out.view());
    ADD_FAILURE() << "mismatched sizes were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("differ in size"), std::string::npos) << e.what();
  }
  DeviceFrame lidarOnly;
  std::vector<LidarSample> samples{{3, 4, 160}};
  lidarOnly.lidar = samples.data();
  lidarOnly.lidarCount = samples.size();
  EXPECT_THROW(matcher->computeOnDevice(lidarOnly, out.view()), std::invalid_argument);  // no size given
}

#ifdef LIDAR_SGM_TEST_CUDA_BACKEND
// The same frame from host memory and from device memory (padded rows, 8 and 16 bits, every
// mode, the disparity to the host and to the device): identical results, equal to cpu_ref's.
TEST(DeviceFrames, CudaDeviceInputsAndOutputsMatchHostInputs) {
  if (!isAvailable(Backend::Cuda)) GTEST_SKIP() << "backend cuda: " << unavailableReason(Backend::Cuda);
  const int width = 131;
  const int height = 61;
  const BackendScene scene = makeBackendScene(width, height, 0, 64, 41);
  std::vector<LidarSample> samples;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (const int* d = scene.lidar.begin(x, y); d != scene.lidar.end(x, y); ++d) samples.push_back({x, y, *d});
    }
  }
  cuda::DeviceMemory deviceSamples(samples.size() * sizeof(LidarSample));
  deviceSamples.upload(samples.data(), samples.size() * sizeof(LidarSample));
  for (const bool sixteen : {false, true}) {
    // The padded host images, byte for byte on the device (same strides).
    const auto onDevice = [](const auto& image, cuda::DeviceMemory& memory) {
      using Pixel = std::remove_const_t<std::remove_reference_t<decltype(image.pixels[0])>>;
      memory.upload(image.pixels.data(), image.pixels.size() * sizeof(Pixel));
      return ImageView<const Pixel>(static_cast<const Pixel*>(memory.data()), image.width, image.height, image.stride);
    };
    const std::size_t bytes = sixteen ? scene.left16.pixels.size() * 2 : scene.left8.pixels.size();
    cuda::DeviceMemory leftMemory(bytes), rightMemory(bytes);
    GrayImageView hostLeft, hostRight, deviceLeft, deviceRight;
    if (sixteen) {
      hostLeft = scene.left16.view();
      hostRight = scene.right16.view();
      deviceLeft = onDevice(scene.left16, leftMemory);
      deviceRight = onDevice(scene.right16, rightMemory);
    } else {
      hostLeft = scene.left8.view();
      hostRight = scene.right8.view();
      deviceLeft = onDevice(scene.left8, leftMemory);
      deviceRight = onDevice(scene.right8, rightMemory);
    }
    for (const std::string mode : {"stereo", "lidar", "fused"}) {
      for (const float scale : {1.0f, 0.5f}) {
        Parameters params;
        params.numDisparities = 64;
        params.scale = scale;
        const bool withRight = mode != "lidar";
        const bool withLidar = mode != "stereo";
        Image<std::int16_t> expected(width, height), fromHost(width, height), fromDevice(width, height);
        Matcher::create(Backend::CpuRef, params)
            ->compute(hostLeft, withRight ? hostRight : GrayImageView(), withLidar ? &scene.lidar : nullptr,
                      expected.view());
        auto matcher = Matcher::create(Backend::Cuda, params);
        matcher->compute(hostLeft, withRight ? hostRight : GrayImageView(), withLidar ? &scene.lidar : nullptr,
                         fromHost.view());
        EXPECT_TRUE(sameImages(expected, fromHost)) << mode << " scale " << scale << (sixteen ? " 16-bit" : "");
        DeviceFrame frame;
        frame.left = deviceLeft;
        if (withRight) frame.right = deviceRight;
        if (withLidar) {
          frame.lidar = static_cast<const LidarSample*>(deviceSamples.data());
          frame.lidarCount = samples.size();
        }
        matcher->computeOnDevice(frame, fromDevice.view());
        EXPECT_TRUE(sameImages(expected, fromDevice)) << mode << " scale " << scale << ", device input";
        Image<std::uint8_t> confidence(width, height);
        for (int y = 0; y < height; ++y) {
          for (int x = 0; x < width; ++x) confidence(x, y) = matcher->confidence()(x, y);
        }
        // The disparity left on the device, in a padded buffer.
        const int stride = width + 5;
        cuda::DeviceMemory outMemory(static_cast<std::size_t>(stride) * height * sizeof(std::int16_t));
        matcher->computeOnDevice(
            frame, ImageView<std::int16_t>(static_cast<std::int16_t*>(outMemory.data()), width, height, stride),
            MemorySpace::Device);
        std::vector<std::int16_t> padded(static_cast<std::size_t>(stride) * height);
        outMemory.download(padded.data(), padded.size() * sizeof(std::int16_t));
        Image<std::int16_t> deviceOut(width, height);
        for (int y = 0; y < height; ++y) {
          for (int x = 0; x < width; ++x) deviceOut(x, y) = padded[static_cast<std::size_t>(y) * stride + x];
        }
        EXPECT_TRUE(sameImages(expected, deviceOut)) << mode << " scale " << scale << ", device output";
        for (int y = 0; y < height; ++y) {
          for (int x = 0; x < width; ++x) ASSERT_EQ(matcher->confidence()(x, y), confidence(x, y)) << x << "," << y;
        }
      }
    }
  }
}

// The caller's stream is still busy when computeOnDevice is called: a long fill, then the copy
// that writes the real images over garbage. The matcher must wait for that stream (and only by
// its event: the caller's stream is non-blocking, so no implicit synchronisation helps).
TEST(DeviceFrames, CudaWaitsForTheCallersStreamBeforeReadingInputs) {
  if (!isAvailable(Backend::Cuda)) GTEST_SKIP() << "backend cuda: " << unavailableReason(Backend::Cuda);
  const int width = 131;
  const int height = 61;
  const BackendScene scene = makeBackendScene(width, height, 0, 64, 43);
  Parameters params;
  params.numDisparities = 64;
  Image<std::int16_t> expected(width, height), fromDevice(width, height);
  Matcher::create(Backend::CpuRef, params)->compute(scene.left8.view(), scene.right8.view(), nullptr, expected.view());
  const std::size_t bytes = scene.left8.pixels.size();
  cuda::DeviceMemory leftSource(bytes), rightSource(bytes), left(bytes), right(bytes);
  leftSource.upload(scene.left8.pixels.data(), bytes);
  rightSource.upload(scene.right8.pixels.data(), bytes);
  auto matcher = Matcher::create(Backend::Cuda, params);
  cuda::DeviceStream caller;
  cuda::DeviceMemory busy(std::size_t{256} << 20);
  for (int round = 0; round < 3; ++round) {
    left.upload(std::vector<std::uint8_t>(bytes, 0x5a).data(), bytes);
    right.upload(std::vector<std::uint8_t>(bytes, 0xa5).data(), bytes);
    for (int i = 0; i < 8; ++i) busy.fillAsync(i, caller);
    left.copyAsync(leftSource, bytes, caller);
    right.copyAsync(rightSource, bytes, caller);
    DeviceFrame frame;
    frame.left = ImageView<const std::uint8_t>(static_cast<const std::uint8_t*>(left.data()), width, height,
                                               scene.left8.stride);
    frame.right = ImageView<const std::uint8_t>(static_cast<const std::uint8_t*>(right.data()), width, height,
                                                scene.right8.stride);
    frame.stream = caller.handle();
    matcher->computeOnDevice(frame, fromDevice.view());
    EXPECT_TRUE(sameImages(expected, fromDevice)) << "round " << round;
    caller.synchronize();
  }
}
#endif

TEST(BackendRegistry, AutoIsTheFastestBackendThatRunsHere) {
  // cuda where a device is present, else cpu where Highway was found, else cpu_ref.
  const Backend expected = isAvailable(Backend::Cuda) ? Backend::Cuda
                           : isAvailable(Backend::Cpu) ? Backend::Cpu
                                                       : Backend::CpuRef;
  EXPECT_EQ(resolve(Backend::Auto), expected);
  EXPECT_EQ(Matcher::create(Backend::Auto)->backend(), expected);
  if (isAvailable(Backend::Cpu)) {
    EXPECT_NE(simdTarget(), "none");
  }
  EXPECT_TRUE(isAvailable(Backend::CpuRef));
  EXPECT_EQ(unavailableReason(Backend::CpuRef), "");
}

// A backend that is built but cannot run here (cuda without a device, as in CI) or is not built
// at all says which, and Matcher::create refuses it instead of failing later.
TEST(BackendRegistry, UnavailableBackendsSayWhy) {
  for (const Backend b : {Backend::Cpu, Backend::Cuda}) {
    const std::string why = unavailableReason(b);
    EXPECT_EQ(isAvailable(b), why.empty());
    if (why.empty()) continue;
    try {
      Matcher::create(b);
      ADD_FAILURE() << toString(b) << " is unavailable (" << why << ") but was created";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(toString(b)), std::string::npos) << e.what();
    }
  }
#ifdef LIDAR_SGM_TEST_CUDA_BACKEND
  // Built: the reason, if any, is the device's, never "not built".
  EXPECT_EQ(unavailableReason(Backend::Cuda).find("not built"), std::string::npos) << unavailableReason(Backend::Cuda);
  if (!isAvailable(Backend::Cuda)) {
    try {
      Matcher::create(Backend::Cuda);
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(unavailableReason(Backend::Cuda)), std::string::npos) << e.what();
    }
  }
#else
  EXPECT_NE(unavailableReason(Backend::Cuda).find("not built"), std::string::npos);
#endif
}

}  // namespace
}  // namespace lidar_sgm
