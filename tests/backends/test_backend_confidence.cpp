// The cpu backend's part of the confidence that the core computes for cpu_ref (LiDAR distance,
// texture and saturation, disparity range, the model's combination), function by function and
// in the one-pass frame version the matcher runs, against the core's functions (the
// specification), bit for bit: odd and tiny sizes, padded strides, 8- and 16-bit images, support
// from none to dense, disparities at the ends of int16, every mode, 1, 2 and 7 threads.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "backend_test_scenes.hpp"
#include "core/confidence_inputs.hpp"
#include "lidar_sgm/core/confidence.hpp"
#include "lidar_sgm/core/matcher.hpp"
#ifdef LIDAR_SGM_TEST_CPU_BACKEND
#include "backends/cpu/cpu_stages.hpp"
#endif

namespace lidar_sgm {
namespace {

template <typename T>
::testing::AssertionResult sameImages(const Image<T>& expected, const Image<T>& actual) {
  if (expected.width() != actual.width() || expected.height() != actual.height()) {
    return ::testing::AssertionFailure() << "sizes differ";
  }
  for (int y = 0; y < expected.height(); ++y) {
    for (int x = 0; x < expected.width(); ++x) {
      if (expected(x, y) != actual(x, y)) {
        return ::testing::AssertionFailure() << "first difference at (" << x << ", " << y << "): core "
                                             << +expected(x, y) << ", cpu " << +actual(x, y);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// The helpers below serve the cpu backend's tests only: unused (and so [[maybe_unused]]) where it
// is not built, as on the GPU machine.
struct Size {
  int width, height;
};
constexpr Size kSizes[] = {{1, 1}, {2, 3}, {5, 4}, {17, 9}, {64, 40}, {131, 47}};

// LiDAR support: none, a band of rows (so that rows far from it exist), sparse, dense.
[[maybe_unused]] Image<std::uint8_t> supportOf(Size s, int kind, std::mt19937& engine) {
  Image<std::uint8_t> support(s.width, s.height, 0);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const bool band = y >= s.height / 2 && y < s.height / 2 + 3 && engine() % 7 == 0;
      const bool on = kind == 1 ? band : kind == 2 ? engine() % 53 == 0 : kind == 3 && engine() % 3 == 0;
      support(x, y) = on ? 1 : 0;
    }
  }
  return support;
}

// Disparities with invalid pixels and the ends of int16 (the range's 16-bit span).
[[maybe_unused]] Image<std::int16_t> disparityOf(Size s, int invalidOneIn, std::mt19937& engine) {
  Image<std::int16_t> disparity(s.width, s.height);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const auto pick = engine() % 50u;
      disparity(x, y) = engine() % static_cast<unsigned>(invalidOneIn) == 0 ? kInvalidDisparity
                        : pick == 0 ? std::int16_t{32767}
                        : pick == 1 ? std::int16_t{-32767}
                                    : static_cast<std::int16_t>(static_cast<int>(engine() % 2048u) - 64);
    }
  }
  return disparity;
}

template <typename T>
Image<T> imageOf(Size s, int maxValue, std::mt19937& engine) {
  Image<T> image(s.width, s.height);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      // Smooth areas, edges and saturated pixels.
      const auto pick = engine() % 10u;
      image(x, y) = static_cast<T>(pick == 0   ? maxValue
                                   : pick < 5 ? (x * 7 + y * 3) % (maxValue / 4)
                                               : static_cast<int>(engine() % static_cast<unsigned>(maxValue + 1)));
    }
  }
  return image;
}

// The core's inputs and confidence of a frame, as the Matcher computes them for cpu_ref.
[[maybe_unused]] void coreConfidence(const GrayImageView& image, const Image<std::uint8_t>& support, const Image<std::int16_t>& disparity,
                    MatchMode mode, int paths, ConfidenceInputs& in, Image<std::uint8_t>& confidence) {
  const int W = disparity.width();
  const int H = disparity.height();
  ConfidenceScratch scratch;
  in.lidarDistance.resize(W, H);
  in.texture.resize(W, H);
  in.saturated.resize(W, H);
  in.disparityRange.resize(W, H);
  confidence.resize(W, H);
  lidarDistance(support.view(), in.lidarDistance.view(), scratch);
  textureAndSaturation(image, in.texture.view(), in.saturated.view(), scratch);
  disparityRange(disparity.view(), in.disparityRange.view(), scratch);
  combineConfidence(in, mode, paths, disparity.view(), confidence.view());
}

// The inputs only the backend's cost volume gives, at random.
[[maybe_unused]] void randomVolumeInputs(Size s, std::mt19937& engine, ConfidenceInputs& in) {
  in.margin = Image<std::uint8_t>(s.width, s.height);
  in.bestCost = Image<std::uint16_t>(s.width, s.height);
  in.leftRightDifference = Image<std::uint8_t>(s.width, s.height);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      in.margin(x, y) = static_cast<std::uint8_t>(engine() % 256u);
      in.bestCost(x, y) = static_cast<std::uint16_t>(engine() % 40000u);
      const auto r = engine() % 12u;
      in.leftRightDifference(x, y) = r >= 10 ? kNoCounterpartDifference : static_cast<std::uint8_t>(r);
    }
  }
}

class CpuConfidence : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
#ifndef LIDAR_SGM_TEST_CPU_BACKEND
    GTEST_SKIP() << "the cpu backend is not built";
#endif
  }
};

#ifdef LIDAR_SGM_TEST_CPU_BACKEND

TEST_P(CpuConfidence, EachInputMatchesTheCore) {
  const int threads = GetParam();
  std::mt19937 engine(17);
  cpu::ConfidenceBuffers buffers;  // one set for every size: grown, never shrunk
  ConfidenceScratch scratch;
  for (const Size s : kSizes) {
    const std::string where = std::to_string(s.width) + "x" + std::to_string(s.height);
    for (int kind = 0; kind < 4; ++kind) {
      const Image<std::uint8_t> support = supportOf(s, kind, engine);
      const test::PaddedImage<std::uint8_t> padded = test::padded(support, 3, std::uint8_t{1});
      Image<std::uint8_t> expected(s.width, s.height), actual(s.width, s.height, 77);
      lidarDistance(support.view(), expected.view(), scratch);
      cpu::lidarDistance(padded.view(), actual.view(), buffers, threads);
      EXPECT_TRUE(sameImages(expected, actual)) << "lidarDistance " << where << " support kind " << kind;
    }
    const Image<std::uint8_t> image8 = imageOf<std::uint8_t>(s, 255, engine);
    const Image<std::uint16_t> image16 = imageOf<std::uint16_t>(s, 65535, engine);
    const test::PaddedImage<std::uint8_t> padded8 = test::padded(image8, 2, std::uint8_t{255});
    const test::PaddedImage<std::uint16_t> padded16 = test::padded(image16, 2, std::uint16_t{65535});
    for (const GrayImageView& image :
         {GrayImageView(padded8.view()), GrayImageView(padded16.view()), GrayImageView()}) {
      Image<std::uint8_t> texture(s.width, s.height), saturated(s.width, s.height);
      Image<std::uint8_t> textureActual(s.width, s.height, 77), saturatedActual(s.width, s.height, 77);
      textureAndSaturation(image, texture.view(), saturated.view(), scratch);
      cpu::textureAndSaturation(image, textureActual.view(), saturatedActual.view(), buffers, threads);
      EXPECT_TRUE(sameImages(texture, textureActual)) << "texture " << where;
      EXPECT_TRUE(sameImages(saturated, saturatedActual)) << "saturated " << where;
    }
    for (const int invalidOneIn : {1000000, 9, 2, 1}) {
      const Image<std::int16_t> disparity = disparityOf(s, invalidOneIn, engine);
      const test::PaddedImage<std::int16_t> padded = test::padded(disparity, 2, std::int16_t{5});
      Image<std::uint8_t> expected(s.width, s.height), actual(s.width, s.height, 77);
      disparityRange(disparity.view(), expected.view(), scratch);
      cpu::disparityRange(padded.view(), actual.view(), buffers, threads);
      EXPECT_TRUE(sameImages(expected, actual)) << "disparityRange " << where << " invalid 1/" << invalidOneIn;
    }
  }
}

TEST_P(CpuConfidence, CombinationAndTheMatchersOnePassMatchTheCore) {
  const int threads = GetParam();
  std::mt19937 engine(23);
  cpu::ConfidenceBuffers buffers;
  for (const Size s : kSizes) {
    const Image<std::uint8_t> support = supportOf(s, 2, engine);
    const Image<std::int16_t> disparity = disparityOf(s, 7, engine);
    const Image<std::uint8_t> image8 = imageOf<std::uint8_t>(s, 255, engine);
    const Image<std::uint16_t> image16 = imageOf<std::uint16_t>(s, 65535, engine);
    for (const MatchMode mode : {MatchMode::StereoOnly, MatchMode::LidarOnly, MatchMode::Fused}) {
      for (const bool sixteen : {false, true}) {
        for (const int paths : {4, 8}) {
          const GrayImageView image = mode == MatchMode::LidarOnly ? GrayImageView()
                                      : sixteen                    ? GrayImageView(image16.view())
                                                                   : GrayImageView(image8.view());
          ConfidenceInputs expected;
          randomVolumeInputs(s, engine, expected);
          Image<std::uint8_t> confidence;
          coreConfidence(image, support, disparity, mode, paths, expected, confidence);
          const std::string where = std::to_string(s.width) + "x" + std::to_string(s.height) + " " +
                                    toString(mode) + (sixteen ? " 16-bit" : " 8-bit") + " paths " +
                                    std::to_string(paths);

          Image<std::uint8_t> combined(s.width, s.height, 77);
          cpu::combineConfidence(expected, mode, paths, disparity.view(), combined.view(), threads);
          EXPECT_TRUE(sameImages(confidence, combined)) << "combineConfidence " << where;

          // The one pass fills the four image inputs and the confidence from the volume's three.
          ConfidenceInputs actual;
          actual.margin = expected.margin;
          actual.bestCost = expected.bestCost;
          actual.leftRightDifference = expected.leftRightDifference;
          actual.lidarDistance = Image<std::uint8_t>(s.width, s.height, 77);
          actual.texture = Image<std::uint8_t>(s.width, s.height, 77);
          actual.saturated = Image<std::uint8_t>(s.width, s.height, 77);
          actual.disparityRange = Image<std::uint8_t>(s.width, s.height, 77);
          Image<std::uint8_t> onePass(s.width, s.height, 77);
          cpu::confidenceOfFrame(image, support.view(), disparity.view(), mode, paths, actual, onePass.view(), buffers,
                                 threads);
          EXPECT_TRUE(sameImages(expected.lidarDistance, actual.lidarDistance)) << "one pass, g " << where;
          EXPECT_TRUE(sameImages(expected.texture, actual.texture)) << "one pass, t " << where;
          EXPECT_TRUE(sameImages(expected.saturated, actual.saturated)) << "one pass, s " << where;
          EXPECT_TRUE(sameImages(expected.disparityRange, actual.disparityRange)) << "one pass, v " << where;
          EXPECT_TRUE(sameImages(confidence, onePass)) << "one pass, confidence " << where;
        }
      }
    }
  }
}

#else

TEST_P(CpuConfidence, EachInputMatchesTheCore) {}
TEST_P(CpuConfidence, CombinationAndTheMatchersOnePassMatchTheCore) {}

#endif

std::string threadsName(const ::testing::TestParamInfo<int>& param) { return std::to_string(param.param) + "threads"; }

INSTANTIATE_TEST_SUITE_P(Threads, CpuConfidence, ::testing::Values(1, 2, 7), threadsName);

}  // namespace
}  // namespace lidar_sgm
