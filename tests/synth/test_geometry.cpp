// The ground truth is exact: the LiDAR, projected with the written calibration, lands on the
// surface the camera sees at the depth the GT says; where it does not, the camera is occluded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "lidar_sgm/synth/frame.hpp"
#include "synth/synth_test_helpers.hpp"

namespace lidar_sgm {
namespace {

const synth::Frame& defaultFrame() {
  static const synth::Frame frame = [] {
    synth::FrameOptions options;
    options.seed = 11;
    return synth::renderFrame(options);
  }();
  return frame;
}

// GT depth at a sub-pixel position by bilinear interpolation of 1/z (exact on planes); false when
// the four pixels are not one smooth surface (an edge or sky).
bool smoothDepthAt(const Image<float>& depth, double u, double v, double& z) {
  const int x0 = static_cast<int>(std::floor(u));
  const int y0 = static_cast<int>(std::floor(v));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= depth.width() || y0 + 1 >= depth.height()) return false;
  const float d[4] = {depth(x0, y0), depth(x0 + 1, y0), depth(x0, y0 + 1), depth(x0 + 1, y0 + 1)};
  const float lo = *std::min_element(d, d + 4);
  const float hi = *std::max_element(d, d + 4);
  if (lo <= 0.0f || hi > 1.05f * lo + 0.05f) return false;
  const double tx = u - x0;
  const double ty = v - y0;
  const double inverse = (1 - ty) * ((1 - tx) / d[0] + tx / d[1]) + ty * ((1 - tx) / d[2] + tx / d[3]);
  z = 1.0 / inverse;
  return true;
}

TEST(SynthGeometry, LidarPointsLieOnTheSurfaceTheCameraSees) {
  const synth::Frame& frame = defaultFrame();
  const test::CalibratedProjector projector(synth::kittiCalibrationText(frame.rig, false));
  std::vector<double> errors;
  for (const synth::LidarPoint& p : frame.lidar) {
    const test::Projection q = projector.project(p);
    double z = 0;
    if (q.z < 1.0 || !smoothDepthAt(frame.depth, q.u, q.v, z)) continue;
    if (z < q.z - 0.5) continue;  // occluded from the camera: counted by the next test
    errors.push_back(std::abs(z - q.z));
  }
  ASSERT_GT(errors.size(), 20000u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  const auto within = static_cast<double>(std::lower_bound(errors.begin(), errors.end(), 0.1) - errors.begin());
  // Range noise sigma 2 cm: median |error| 0.67 sigma, and almost all within 5 sigma.
  EXPECT_LT(median, 0.02);
  EXPECT_GT(median, 0.005);  // the noise is there
  EXPECT_GT(within / static_cast<double>(errors.size()), 0.995);
}

TEST(SynthGeometry, SomeLidarPointsAreHiddenFromTheCameraNearDepthEdges) {
  const synth::Frame& frame = defaultFrame();
  const test::CalibratedProjector projector(synth::kittiCalibrationText(frame.rig, false));
  long inImage = 0;
  long occluded = 0;
  long occludedNearEdge = 0;
  for (const synth::LidarPoint& p : frame.lidar) {
    const test::Projection q = projector.project(p);
    const int x = static_cast<int>(std::lround(q.u));
    const int y = static_cast<int>(std::lround(q.v));
    if (q.z < 1.0 || x < 0 || y < 0 || x >= frame.rig.width || y >= frame.rig.height) continue;
    ++inImage;
    const float z = frame.depth(x, y);
    if (!(z > 0.0f && z < 0.9 * q.z - 0.5)) continue;
    ++occluded;
    // Parallax hides a point only behind a nearer surface's edge: a depth jump must be close by.
    float lo = z;
    float hi = z;
    for (int dy = -8; dy <= 8; ++dy) {
      for (int dx = -8; dx <= 8; ++dx) {
        const int xx = std::clamp(x + dx, 0, frame.rig.width - 1);
        const int yy = std::clamp(y + dy, 0, frame.rig.height - 1);
        const float d = frame.depth(xx, yy);
        if (d <= 0.0f) continue;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
    occludedNearEdge += hi > 1.2f * lo ? 1 : 0;
  }
  ASSERT_GT(inImage, 20000);
  EXPECT_GT(occluded, 0) << "the LiDAR sits 0.27 m behind and 0.08 m above the camera: parallax must hide some points";
  EXPECT_LT(static_cast<double>(occluded) / static_cast<double>(inImage), 0.03);
  EXPECT_GT(static_cast<double>(occludedNearEdge) / static_cast<double>(std::max(1L, occluded)), 0.9);
}

TEST(SynthGeometry, DisparityIsFocalTimesBaselineOverDepthAndSkyHasNone) {
  const synth::Frame& frame = defaultFrame();
  long sky = 0;
  for (int y = 0; y < frame.rig.height; ++y) {
    for (int x = 0; x < frame.rig.width; ++x) {
      const float z = frame.depth(x, y);
      if (z <= 0.0f) {
        EXPECT_EQ(frame.disparity(x, y), 0.0f);
        EXPECT_EQ(frame.objectMask(x, y), 0);
        ++sky;
        continue;
      }
      ASSERT_NEAR(frame.disparity(x, y), frame.rig.focal * frame.rig.baseline / z, 1e-3);
    }
  }
  // The top rows are sky somewhere (the street is open above), the bottom row is road.
  EXPECT_GT(sky, 0);
  for (int x = 0; x < frame.rig.width; ++x) ASSERT_GT(frame.depth(x, frame.rig.height - 1), 0.0f);
}

TEST(SynthGeometry, ObjectMaskCoversObjectsButNotBackground) {
  const synth::Frame& frame = defaultFrame();
  long objects = 0;
  for (int y = 0; y < frame.rig.height; ++y) {
    for (int x = 0; x < frame.rig.width; ++x) objects += frame.objectMask(x, y);
  }
  const double share = static_cast<double>(objects) / (static_cast<double>(frame.rig.width) * frame.rig.height);
  EXPECT_GT(share, 0.005);
  EXPECT_LT(share, 0.5);
}

TEST(SynthGeometry, WrittenCalibrationDescribesTheRig) {
  const synth::StereoRig rig = synth::StereoRig::kittiLike(1242, 375, 0.8);
  const auto rows = test::parseCalibration(synth::kittiCalibrationText(rig, true));
  ASSERT_EQ(rows.at("P2").size(), 12u);
  EXPECT_NEAR(rows.at("P2")[0], 721.5377, 1e-9);
  EXPECT_NEAR(rows.at("P2")[2], 609.5593, 1e-9);
  EXPECT_NEAR(rows.at("P2")[6], 172.854, 1e-9);
  EXPECT_NEAR(rows.at("P3")[3], -721.5377 * 0.8, 1e-9);
  EXPECT_NEAR(rows.at("P_up")[7], 721.5377 * 0.2, 1e-9);
  // LiDAR 0.27 m behind and 0.08 m above the camera: its origin is at camera (0, -0.08, -0.27).
  const std::vector<double>& t = rows.at("Tr_velo_to_cam");
  EXPECT_NEAR(t[3], 0.0, 1e-12);
  EXPECT_NEAR(t[7], -0.08, 1e-12);
  EXPECT_NEAR(t[11], -0.27, 1e-12);
  EXPECT_EQ(rows.count("P_up"), 1u);
  EXPECT_EQ(test::parseCalibration(synth::kittiCalibrationText(rig, false)).count("P_up"), 0u);
}

}  // namespace
}  // namespace lidar_sgm
