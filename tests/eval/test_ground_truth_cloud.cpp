// A frame's methods scored in 3D against its GT as a cloud (the KITTI142 protocol), on a frame
// whose clouds are two known planes.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "lidar_sgm/eval/ground_truth_cloud.hpp"

namespace lidar_sgm {
namespace {

/// 40x30, f = 100 px, b = 0.5 m (f*b = 50): GT 10 px (a wall at 5 m) on rows 15..29 only, none above.
eval::EvalFrame planeFrame() {
  eval::EvalFrame frame;
  frame.dataset = "planes";
  frame.name = "000000";
  geometry::StereoCalibration c;
  c.width = 40;
  c.height = 30;
  c.K << 100, 0, 20, 0, 100, 15, 0, 0, 1;
  c.baseline = 0.5;
  frame.calibration = c;
  frame.focalBaseline = c.focalBaseline();
  frame.groundTruth = Image<float>(40, 30, 0.0f);
  for (int y = 15; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) frame.groundTruth(x, y) = 10.0f;
  }
  return frame;
}

std::size_t tauIndex(const eval::CloudDistanceScore& s, double tau) {
  for (std::size_t t = 0; t < s.overall.scores.size(); ++t) {
    if (s.overall.scores[t].tau == tau) return t;
  }
  ADD_FAILURE() << "no tau " << tau;
  return 0;
}

// A disparity equal to the GT everywhere it has one, and points above it where the GT has none:
// those are not judged (KITTI did not measure there) but the GT is complete.
TEST(GroundTruthCloud, ExactDisparityScoresOneAndPointsWithoutGtAreNotJudged) {
  const eval::EvalFrame frame = planeFrame();
  const eval::GroundTruthCloud reference(frame);
  EXPECT_EQ(reference.size(), 40u * 15u);
  const Image<std::int16_t> disparity(40, 30, 160);  // 10 px everywhere
  const std::optional<eval::CloudDistanceScore> s = reference.score(disparity.view());
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->overall.points, 40 * 15);
  EXPECT_EQ(s->unjudgedPoints, 40 * 15);
  EXPECT_EQ(s->overall.referencePoints, 40 * 15);
  for (const eval::CloudDistanceAtTau& at : s->overall.scores) {
    EXPECT_EQ(at.precision, 1.0) << at.tau;
    EXPECT_EQ(at.completeness, 1.0) << at.tau;
  }
  EXPECT_EQ(s->overall.medianDistance, 0.0);
  ASSERT_EQ(s->bands.size(), 4u);
  EXPECT_EQ(s->bands[0].referencePoints, 40 * 15);  // every point within 10 m of the camera
}

// 9.375 px puts the wall at 5.333 m, 0.333 m behind the GT's: wrong at tau 0.1 and 0.2 m, right
// at 0.5 m; no disparity at all is no score.
TEST(GroundTruthCloud, WallBehindTheGtFlipsBetweenTaus) {
  const eval::EvalFrame frame = planeFrame();
  const eval::GroundTruthCloud reference(frame);
  const std::optional<eval::CloudDistanceScore> s = reference.score(Image<std::int16_t>(40, 30, 150).view());
  ASSERT_TRUE(s.has_value());
  for (double tau : {0.1, eval::kGroundTruthCloudTau}) {
    EXPECT_EQ(s->overall.scores[tauIndex(*s, tau)].precision, 0.0) << tau;
    EXPECT_EQ(s->overall.scores[tauIndex(*s, tau)].completeness, 0.0) << tau;
  }
  EXPECT_EQ(s->overall.scores[tauIndex(*s, 0.5)].fScore, 1.0);
  EXPECT_NEAR(s->overall.medianDistance, 50.0 / 9.375 - 5.0, 0.01);
  EXPECT_FALSE(reference.score(Image<std::int16_t>(40, 30, kInvalidDisparity).view()).has_value());
}

TEST(GroundTruthCloud, FrameWithoutCalibrationOrGtIsRefused) {
  eval::EvalFrame frame = planeFrame();
  frame.calibration.reset();
  EXPECT_THROW(eval::GroundTruthCloud{frame}, std::invalid_argument);
  frame = planeFrame();
  frame.groundTruth.fill(0.0f);
  EXPECT_THROW(eval::GroundTruthCloud{frame}, std::invalid_argument);
}

}  // namespace
}  // namespace lidar_sgm
