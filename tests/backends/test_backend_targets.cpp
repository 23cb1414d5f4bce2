// The cpu backend's kernels are compiled once per SIMD target (Highway) and one is chosen at run
// time, so a machine tests only its own unless told otherwise: every target this build holds and
// this CPU runs (AVX-512, AVX2, SSE4, ... and the portable fallback) gives cpu_ref's frames bit
// for bit, on frames that take each kernel's widths: 80 disparities (a 64-, 32- or 16-byte block
// and a tail), 16-bit path costs, narrow gated windows, 8 paths, a stereo-only left-right check.
#include <gtest/gtest.h>

#ifdef LIDAR_SGM_TEST_CPU_BACKEND
#include <hwy/targets.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "backend_test_scenes.hpp"
#include "lidar_sgm/core/matcher.hpp"

namespace lidar_sgm {
namespace {

struct TargetCase {
  const char* name;
  bool stereoOnly;
  std::function<void(Parameters&)> tweak;
};

// Restores the run-time choice of target whatever the test does.
struct ChosenTarget {
  explicit ChosenTarget(std::int64_t target) { hwy::SetSupportedTargetsForTest(target); }
  ~ChosenTarget() { hwy::SetSupportedTargetsForTest(0); }
};

TEST(BackendTargets, EveryCompiledTargetMatchesCpuRef) {
  const std::vector<TargetCase> cases = {
      {"Disparities80", false, [](Parameters& p) { p.numDisparities = 80; p.gatedSearch = false; }},
      {"LargePenalties16BitPaths", false,
       [](Parameters& p) { p.numDisparities = 64; p.P1 = 3000; p.P2 = 4000; p.lidarCostCap = 255; p.gatedSearch = false; }},
      {"GatedNarrowWindows", false,
       [](Parameters& p) { p.numDisparities = 96; p.gatedSearch = true; p.gatedSearchMargin = 0; p.gatedSearchRows = 1; }},
      {"EightPathsGated", false, [](Parameters& p) { p.numDisparities = 64; p.paths = 8; p.gatedSearch = true; }},
      {"StereoLeftRightCheck", true, [](Parameters& p) { p.numDisparities = 128; p.uniquenessRatio = 10; }},
  };
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (const std::int64_t target : targets) {
    const ChosenTarget chosen(target);
    for (const TargetCase& c : cases) {
      Parameters params;
      c.tweak(params);
      params.threads = 2;
      const int width = 131;
      const int height = 61;
      const test::BackendScene scene = test::makeBackendScene(width, height, params.minDisparity, params.numDisparities, 7);
      const GrayImageView left(scene.left8.view());
      const GrayImageView right(scene.right8.view());
      const LidarPoints* lidar = c.stereoOnly ? nullptr : &scene.lidar;
      auto reference = Matcher::create(Backend::CpuRef, params);
      auto backend = Matcher::create(Backend::Cpu, params);
      Image<std::int16_t> expected(width, height), actual(width, height);
      reference->compute(left, right, VerticalView{}, lidar, expected.view());
      backend->compute(left, right, VerticalView{}, lidar, actual.view());
      int differences = 0;
      int valid = 0;
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          differences += expected(x, y) != actual(x, y) ? 1 : 0;
          valid += expected(x, y) != kInvalidDisparity ? 1 : 0;
        }
      }
      EXPECT_EQ(differences, 0) << hwy::TargetName(target) << ", " << c.name;
      EXPECT_GT(valid, width * height / 3) << c.name;
    }
  }
}

}  // namespace
}  // namespace lidar_sgm
#endif
