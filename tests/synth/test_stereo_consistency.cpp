// The GT disparity maps left pixels onto the right pixels of the same surface (and the third
// camera sees the same surface f*0.20/z rows lower).
#include <gtest/gtest.h>

#include <cmath>

#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/frame.hpp"
#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace {

double sampleRow(const Image<std::uint8_t>& image, double x, int y) {
  const int x0 = static_cast<int>(std::floor(x));
  const double t = x - x0;
  return (1 - t) * image(x0, y) + t * image(x0 + 1, y);
}

double sampleColumn(const Image<std::uint8_t>& image, int x, double y) {
  const int y0 = static_cast<int>(std::floor(y));
  const double t = y - y0;
  return (1 - t) * image(x, y0) + t * image(x, y0 + 1);
}

struct Photometric {
  double atGt = 0;
  double shifted = 0;
  long pixels = 0;
};

// Mean |L(x) - R(x - d - offset)| over left pixels whose surface the right camera also sees.
Photometric compareRight(const synth::Frame& frame, const Image<float>& rightDepth, double offset) {
  const Image<std::uint8_t> left = synth::toGray(frame.left);
  const Image<std::uint8_t> right = synth::toGray(frame.right);
  Photometric p;
  for (int y = 0; y < frame.rig.height; ++y) {
    for (int x = 0; x < frame.rig.width; ++x) {
      const double d = frame.disparity(x, y);
      if (d <= 0) continue;
      const double xr = x - d;
      if (xr < 4 || xr > frame.rig.width - 6) continue;
      const float zr = rightDepth(static_cast<int>(std::lround(xr)), y);
      if (std::abs(zr - frame.depth(x, y)) > 0.02f * frame.depth(x, y)) continue;  // occluded in the right view
      p.atGt += std::abs(left(x, y) - sampleRow(right, xr, y));
      p.shifted += std::abs(left(x, y) - sampleRow(right, xr - offset, y));
      ++p.pixels;
    }
  }
  p.atGt /= static_cast<double>(p.pixels);
  p.shifted /= static_cast<double>(p.pixels);
  return p;
}

TEST(SynthStereo, GroundTruthDisparityMatchesLeftToRight) {
  for (double baseline : {0.54, 0.80}) {
    synth::FrameOptions options;
    options.seed = 3;
    options.baseline = baseline;
    const synth::Frame frame = synth::renderFrame(options);
    const synth::Scene scene = synth::makeStreetScene(options.seed);
    const Image<float> rightDepth = synth::renderView(scene, frame.rig.right(), options.weather, 0).depth;
    const Photometric p = compareRight(frame, rightDepth, 3.0);
    ASSERT_GT(p.pixels, 300000);
    EXPECT_LT(p.atGt, 2.5) << "baseline " << baseline;
    EXPECT_GT(p.shifted, 3.0 * p.atGt) << "baseline " << baseline;
  }
}

TEST(SynthStereo, ThirdCameraSeesTheSameSurfaceLower) {
  synth::FrameOptions options;
  options.seed = 4;
  options.thirdCamera = true;
  const synth::Frame frame = synth::renderFrame(options);
  ASSERT_EQ(frame.up.width(), frame.rig.width);
  const Image<std::uint8_t> left = synth::toGray(frame.left);
  const Image<std::uint8_t> up = synth::toGray(frame.up);
  double atGt = 0;
  double shifted = 0;
  long pixels = 0;
  for (int y = 0; y < frame.rig.height; ++y) {
    for (int x = 0; x < frame.rig.width; ++x) {
      const float z = frame.depth(x, y);
      if (z <= 0.0f || frame.objectMask(x, y) != 0) continue;  // objects: possible occlusions
      const double yu = y + frame.rig.focal * frame.rig.thirdCameraOffset / z;  // camera above: scene lower
      if (yu > frame.rig.height - 6) continue;
      atGt += std::abs(left(x, y) - sampleColumn(up, x, yu));
      shifted += std::abs(left(x, y) - sampleColumn(up, x, yu + 3.0));
      ++pixels;
    }
  }
  ASSERT_GT(pixels, 100000);
  EXPECT_LT(atGt / static_cast<double>(pixels), 3.0);
  EXPECT_GT(shifted, 2.0 * atGt);
}

}  // namespace
}  // namespace lidar_sgm
