// The evaluation's methods: stable ids, and the LiDAR-SGM methods run exactly as the tools run
// them (through the Densifier, LiDAR-only cropped to the scan).
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/eval/methods.hpp"
#include "lidar_sgm/eval/protocols.hpp"
#include "lidar_sgm/io/image_io.hpp"
#include "lidar_sgm/pipeline/densifier.hpp"

namespace lidar_sgm {
namespace eval {
namespace {

/// One small synthetic frame with a third camera (P3), rendered once.
const EvalFrame& smallFrame() {
  static const EvalFrame frame = [] {
    P3Options options;
    options.frames = 1;
    options.thirdCamera = true;
    options.width = 310;
    options.height = 94;
    return loadP3(options).at(0);
  }();
  return frame;
}

bool sameImage(const Image<std::int16_t>& a, const Image<std::int16_t>& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      if (a(x, y) != b(x, y)) return false;
    }
  }
  return true;
}

int validInRow(const Image<std::int16_t>& d, int y) {
  int valid = 0;
  for (int x = 0; x < d.width(); ++x) valid += d(x, y) != kInvalidDisparity ? 1 : 0;
  return valid;
}

TEST(MethodIds, EveryKindHasAUniqueIdThatParsesBack) {
  std::set<std::string> ids;
  for (MethodKind kind : allMethodKinds()) {
    const std::string id = methodId(kind);
    EXPECT_TRUE(ids.insert(id).second) << id;
    EXPECT_EQ(methodKindFromId(id), kind) << id;
    EXPECT_EQ(id.find(' '), std::string::npos) << id;
  }
  EXPECT_EQ(methodId(MethodKind::StereoSgm), std::string("stereo_sgm"));
  EXPECT_EQ(methodId(MethodKind::FusedSgm), std::string("fused_sgm"));
}

TEST(MethodIds, DisplayNamesAreNotIds) {
  try {
    methodKindFromId("LiDAR-SGM (alpha 0.7)");
    FAIL() << "a display name must not parse as a method";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fused_sgm"), std::string::npos) << e.what();  // lists the ids
  }
  EXPECT_EQ(displayName({MethodKind::FusedSgm, 0.7}), "LiDAR-SGM (alpha 0.7)");
  EXPECT_TRUE(sameMethod({MethodKind::StereoSgm, 0.0}, {MethodKind::StereoSgm, 0.7}));  // alpha is not its
  EXPECT_FALSE(sameMethod({MethodKind::FusedSgm, 0.7}, {MethodKind::FusedSgm, 0.5}));
}

/// What lidar_sgm_densify does with the same inputs: a Densifier with its defaults.
Image<std::int16_t> densify(const EvalFrame& f, bool images, bool lidar, bool up, float alpha) {
  Densifier densifier;
  densifier.parameters().numDisparities = f.numDisparities;
  densifier.parameters().alpha = alpha;
  densifier.setComputeCloud(false);
  if (images) densifier.setStereoPair(io::grayView(f.left), io::grayView(f.right));
  if (up) densifier.setUpCamera(io::grayView(f.up), f.upBaselineRatio);
  densifier.runProjected(lidar ? &f.lidar : nullptr);
  return densifier.disparity();
}

TEST(RunMethod, TheLidarSgmMethodsAreTheDensifiers) {
  const EvalFrame& f = smallFrame();
  EXPECT_TRUE(sameImage(runMethod({MethodKind::StereoSgm, 0.0}, f).disparity, densify(f, true, false, false, 0.0f)));
  EXPECT_TRUE(sameImage(runMethod({MethodKind::LidarSgm, 1.0}, f).disparity, densify(f, false, true, false, 1.0f)));
  EXPECT_TRUE(sameImage(runMethod({MethodKind::FusedSgm, 0.7}, f).disparity, densify(f, true, true, false, 0.7f)));
  EXPECT_TRUE(sameImage(runMethod({MethodKind::FusedSgm, 0.3}, f).disparity, densify(f, true, true, false, 0.3f)));
  EXPECT_TRUE(sameImage(runMethod({MethodKind::ThreeCameras, 0.0}, f).disparity, densify(f, true, false, true, 0.0f)));
  EXPECT_TRUE(
      sameImage(runMethod({MethodKind::ThreeCamerasLidar, 0.7}, f).disparity, densify(f, true, true, true, 0.7f)));
  // The alpha of a method is its own: the fused method at 0.3 is not the one at 0.7.
  EXPECT_FALSE(sameImage(runMethod({MethodKind::FusedSgm, 0.3}, f).disparity, densify(f, true, true, false, 0.7f)));
}

TEST(RunMethod, LidarOnlyIsCroppedAboveTheTopBeamAsTheToolShipsIt) {
  const EvalFrame& f = smallFrame();
  // The matcher alone fills the rows above the scan (SGM's vertical paths carry the top beam up).
  Parameters params;
  params.numDisparities = f.numDisparities;
  params.alpha = 1.0f;
  auto matcher = Matcher::create(Backend::Auto, params);
  Image<std::int16_t> uncropped(f.left.cols, f.left.rows, kInvalidDisparity);
  matcher->compute(GrayImageView(), GrayImageView(), &f.lidar, uncropped.view());
  ASSERT_GT(validInRow(uncropped, 0), 0) << "the frame does not show the crop: its top row is empty anyway";

  const Image<std::int16_t> shipped = runMethod({MethodKind::LidarSgm, 1.0}, f).disparity;
  EXPECT_EQ(validInRow(shipped, 0), 0);
  int topInput = f.lidar.height();
  for (int y = 0; y < f.lidar.height() && topInput == f.lidar.height(); ++y) {
    for (int x = 0; x < f.lidar.width(); ++x) {
      if (f.lidar.count(x, y) > 0) {
        topInput = y;
        break;
      }
    }
  }
  EXPECT_GT(validInRow(shipped, topInput), 0);  // the scan itself stays
}

TEST(RunMethod, AMissingThirdCameraIsAnError) {
  EvalFrame f = smallFrame();
  f.up = cv::Mat();
  EXPECT_THROW(runMethod({MethodKind::ThreeCameras, 0.0}, f), std::invalid_argument);
}

}  // namespace
}  // namespace eval
}  // namespace lidar_sgm
