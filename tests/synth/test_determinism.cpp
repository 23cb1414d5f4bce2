// Same seed, same frame, bit for bit; another seed, another street; weather leaves geometry alone.
#include <gtest/gtest.h>

#include <cstring>

#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"

namespace lidar_sgm {
namespace {

template <typename T>
bool samePixels(const Image<T>& a, const Image<T>& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(a.width()) * a.height()) == 0;
}

synth::FrameOptions smallOptions(std::uint32_t seed) {
  synth::FrameOptions o;
  o.seed = seed;
  o.width = 414;
  o.height = 125;
  return o;
}

TEST(SynthDeterminism, SameSeedGivesIdenticalFrames) {
  for (synth::Weather weather : {synth::Weather::Clear, synth::Weather::Rain}) {
    synth::FrameOptions options = smallOptions(21);
    options.weather = weather;
    options.thirdCamera = true;
    const synth::Frame a = synth::renderFrame(options);
    const synth::Frame b = synth::renderFrame(options);
    EXPECT_TRUE(samePixels(a.left, b.left));
    EXPECT_TRUE(samePixels(a.right, b.right));
    EXPECT_TRUE(samePixels(a.up, b.up));
    EXPECT_TRUE(samePixels(a.disparity, b.disparity));
    EXPECT_TRUE(samePixels(a.depth, b.depth));
    EXPECT_TRUE(samePixels(a.objectMask, b.objectMask));
    EXPECT_EQ(synth::velodyneBytes(a.lidar), synth::velodyneBytes(b.lidar));
  }
}

TEST(SynthDeterminism, DifferentSeedsGiveDifferentStreets) {
  const synth::Frame a = synth::renderFrame(smallOptions(1));
  const synth::Frame b = synth::renderFrame(smallOptions(2));
  long different = 0;
  for (int y = 0; y < a.depth.height(); ++y) {
    for (int x = 0; x < a.depth.width(); ++x) different += std::abs(a.depth(x, y) - b.depth(x, y)) > 0.5f ? 1 : 0;
  }
  EXPECT_GT(different, a.depth.width() * a.depth.height() / 10);
  EXPECT_NE(synth::velodyneBytes(a.lidar), synth::velodyneBytes(b.lidar));
}

TEST(SynthDeterminism, RainChangesImagesOnly) {
  synth::FrameOptions options = smallOptions(5);
  const synth::Frame clear = synth::renderFrame(options);
  options.weather = synth::Weather::Rain;
  const synth::Frame rain = synth::renderFrame(options);
  EXPECT_FALSE(samePixels(clear.left, rain.left));
  EXPECT_FALSE(samePixels(clear.right, rain.right));
  EXPECT_TRUE(samePixels(clear.disparity, rain.disparity));
  EXPECT_TRUE(samePixels(clear.objectMask, rain.objectMask));
  EXPECT_EQ(synth::velodyneBytes(clear.lidar), synth::velodyneBytes(rain.lidar));
}

TEST(SynthDeterminism, LidarOptions) {
  synth::FrameOptions options = smallOptions(8);
  const synth::Frame hdl = synth::renderFrame(options);
  options.beams = 128;
  const synth::Frame dense = synth::renderFrame(options);
  EXPECT_GT(dense.lidar.size(), hdl.lidar.size());
  // 245 m and +15 deg: the 128-beam sensor also sees high facades and the far end.
  float highest64 = -1e9f;
  float highest128 = -1e9f;
  for (const auto& p : hdl.lidar) highest64 = std::max(highest64, p.z);
  for (const auto& p : dense.lidar) highest128 = std::max(highest128, p.z);
  EXPECT_GT(highest128, highest64);
  options.lidarInCameraViewOnly = true;
  const synth::Frame inView = synth::renderFrame(options);
  EXPECT_LT(inView.lidar.size(), dense.lidar.size());
  EXPECT_EQ(inView.lidar.size(), synth::keepInCameraView(dense.lidar, dense.rig).size());
}

TEST(SynthDeterminism, InvalidOptionsAreRejectedWithTheirName) {
  synth::FrameOptions options;
  options.beams = 32;
  EXPECT_THROW(synth::renderFrame(options), std::invalid_argument);
  options = {};
  options.baseline = 0.0;
  EXPECT_THROW(synth::validate(options), std::invalid_argument);
  options = {};
  options.width = 8;
  EXPECT_THROW(synth::validate(options), std::invalid_argument);
  EXPECT_THROW(synth::weatherFromString("snow"), std::invalid_argument);
  EXPECT_NO_THROW(synth::validate(synth::FrameOptions{}));
}

}  // namespace
}  // namespace lidar_sgm
