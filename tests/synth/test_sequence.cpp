// A drive along one street: deterministic frames, poses that carry every frame's LiDAR and ground
// truth back onto the one static scene, and a street long and free enough for the whole drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_sgm/synth/encoding.hpp"
#include "lidar_sgm/synth/sequence.hpp"
#include "synth/synth_test_helpers.hpp"

namespace lidar_sgm {
namespace {

using Eigen::Vector3d;

template <typename T>
bool samePixels(const Image<T>& a, const Image<T>& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(a.width()) * a.height()) == 0;
}

synth::SequenceOptions smallDrive(std::uint32_t seed, int frames) {
  synth::SequenceOptions o;
  o.frame.seed = seed;
  o.frame.width = 310;
  o.frame.height = 94;
  o.frames = frames;
  return o;
}

// Tr of the written odometry calib.txt: the LiDAR frame into camera 0 (the left camera).
Eigen::Isometry3d lidarToCamera(const synth::SequenceOptions& options) {
  const synth::StereoRig rig =
      synth::StereoRig::kittiLike(options.frame.width, options.frame.height, options.frame.baseline);
  const std::vector<double> tr = test::parseCalibration(synth::kittiOdometryCalibrationText(rig, false)).at("Tr");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) t.matrix()(r, c) = tr[static_cast<std::size_t>(4 * r + c)];
  }
  return t;
}

// Share of frame `index`'s LiDAR points within `tolerance` of the scene when mapped into the
// world with `pose` (frame index's camera -> camera 0).
double shareOnSurface(const synth::Scene& scene, const synth::SequenceOptions& options, const synth::Frame& frame,
                      const Eigen::Isometry3d& pose, double tolerance) {
  const Eigen::Isometry3d toWorld = synth::worldFromFirstCamera(options) * pose * lidarToCamera(options);
  long near = 0;
  for (const synth::LidarPoint& p : frame.lidar) {
    near += scene.distanceToSurface(toWorld * Vector3d(p.x, p.y, p.z)) < tolerance ? 1 : 0;
  }
  return static_cast<double>(near) / static_cast<double>(std::max<std::size_t>(1, frame.lidar.size()));
}

TEST(SynthSequence, SameOptionsGiveIdenticalFramesWithOrWithoutASharedScene) {
  const synth::SequenceOptions options = smallDrive(3, 4);
  const synth::Scene street = synth::makeSequenceScene(options);
  const synth::Frame shared = synth::renderSequenceFrame(street, options, 2);
  const synth::Frame alone = synth::renderSequenceFrame(options, 2);
  EXPECT_TRUE(samePixels(shared.left, alone.left));
  EXPECT_TRUE(samePixels(shared.right, alone.right));
  EXPECT_TRUE(samePixels(shared.depth, alone.depth));
  EXPECT_TRUE(samePixels(shared.disparity, alone.disparity));
  EXPECT_TRUE(samePixels(shared.objectMask, alone.objectMask));
  EXPECT_EQ(synth::velodyneBytes(shared.lidar), synth::velodyneBytes(alone.lidar));
  // The next frame sees the street from 0.8 m further on: other images, another LiDAR noise.
  const synth::Frame next = synth::renderSequenceFrame(street, options, 3);
  EXPECT_FALSE(samePixels(shared.left, next.left));
  EXPECT_FALSE(samePixels(shared.depth, next.depth));
  EXPECT_NE(synth::velodyneBytes(shared.lidar), synth::velodyneBytes(next.lidar));
}

TEST(SynthSequence, PosesAreTheDriveAlongTheStreet) {
  synth::SequenceOptions options = smallDrive(0, 5);
  options.step = 1.25;
  for (int i = 0; i < options.frames; ++i) {
    const Eigen::Isometry3d pose = synth::sequencePose(options, i);
    EXPECT_TRUE(pose.linear().isIdentity(0.0)) << i;  // straight: no rotation
    // KITTI camera axes: forward is +z.
    EXPECT_LT((pose.translation() - Vector3d(0.0, 0.0, 1.25 * i)).norm(), 1e-12) << i;
  }
  // Camera 0 stands 1.65 m above the road origin, looking along the street (+x world).
  const Eigen::Isometry3d toWorld = synth::worldFromFirstCamera(options);
  EXPECT_TRUE((toWorld * Vector3d::Zero()).isApprox(Vector3d(0.0, 0.0, 1.65)));
  EXPECT_TRUE(toWorld.linear().col(2).isApprox(Vector3d::UnitX()));   // forward
  EXPECT_TRUE(toWorld.linear().col(0).isApprox(-Vector3d::UnitY()));  // right
  EXPECT_TRUE(toWorld.linear().col(1).isApprox(-Vector3d::UnitZ()));  // down
}

// The LiDAR of every frame, carried into frame 0 by the poses and into the world, lies on the one
// scene; with another frame's pose it does not.
TEST(SynthSequence, LidarOfEveryFrameLiesOnTheSceneThroughThePoses) {
  synth::SequenceOptions options = smallDrive(7, 12);
  options.frame.lidarRangeNoise = 0.0;  // exact ranges: the points are on the surfaces
  const synth::Scene street = synth::makeSequenceScene(options);
  for (int i : {0, 5, 11}) {
    const synth::Frame frame = synth::renderSequenceFrame(street, options, i);
    ASSERT_GT(frame.lidar.size(), 50000u);
    EXPECT_GT(shareOnSurface(street, options, frame, synth::sequencePose(options, i), 0.01), 0.999) << i;
    if (i > 0) {
      // 0.8 m off: the road and the facades along the street stay on the scene, the surfaces
      // facing the car do not (measured: 89 % of the points left within 1 cm).
      const double wrong = shareOnSurface(street, options, frame, synth::sequencePose(options, i - 1), 0.01);
      EXPECT_LT(wrong, 0.95) << i;
    }
  }
}

// Pixel (u, v) at its GT depth, carried back through the poses, is a point of the scene.
TEST(SynthSequence, GroundTruthDepthOfEveryFrameIsOnTheScene) {
  const synth::SequenceOptions options = smallDrive(2, 20);
  const synth::Scene street = synth::makeSequenceScene(options);
  for (int i : {1, 19}) {
    const synth::Frame frame = synth::renderSequenceFrame(street, options, i);
    const Eigen::Isometry3d toWorld = synth::worldFromFirstCamera(options) * synth::sequencePose(options, i);
    long pixels = 0;
    double worst = 0.0;
    for (int v = 0; v < frame.rig.height; ++v) {
      for (int u = 0; u < frame.rig.width; ++u) {
        const double z = frame.depth(u, v);
        if (z <= 0.0) continue;
        const Vector3d camera{(u - frame.rig.cx) / frame.rig.focal * z, (v - frame.rig.cy) / frame.rig.focal * z, z};
        worst = std::max(worst, street.distanceToSurface(toWorld * camera) / z);
        ++pixels;
      }
    }
    EXPECT_GT(pixels, frame.rig.width * frame.rig.height / 2) << i;
    EXPECT_LT(worst, 1e-6) << i;  // the depth is a float: relative rounding 6e-8
  }
}

// The street ends 110..180 m past the last frame, and nothing stands in the ego lane to drive into.
TEST(SynthSequence, TheStreetIsLongAndFreeForTheWholeDrive) {
  for (std::uint32_t seed = 0; seed < 6; ++seed) {
    synth::SequenceOptions options = smallDrive(seed, 250);
    const synth::Scene street = synth::makeSequenceScene(options);
    const double lastX = (options.frames - 1) * options.step;
    EXPECT_GE(street.road().endX - lastX, 110.0) << seed;
    EXPECT_LE(street.road().endX - lastX, 180.0) << seed;
    for (double x = -1.0; x <= lastX + 10.0; x += 0.25) {
      for (double z : {0.8, 1.2, 1.65, 2.2}) {
        // Only the road below: the nearest surface is at most as near as the road.
        ASSERT_GE(street.distanceToSurface({x, 0.0, z}), std::min(z, 0.8)) << "seed " << seed << " x " << x;
      }
    }
  }
}

TEST(SynthSequence, ASingleFrameStreetIsUnchanged) {
  const synth::Scene alone = synth::makeStreetScene(9);
  const synth::Scene drive = synth::makeStreetScene(9, 0.0);
  ASSERT_EQ(alone.primitives().size(), drive.primitives().size());
  for (std::size_t i = 0; i < alone.primitives().size(); ++i) {
    EXPECT_TRUE(alone.primitives()[i].center == drive.primitives()[i].center) << i;
    EXPECT_TRUE(alone.primitives()[i].half == drive.primitives()[i].half) << i;
  }
  EXPECT_EQ(alone.road().endX, drive.road().endX);
}

TEST(SynthSequence, BadOptionsAreRejectedByName) {
  const auto message = [](const synth::SequenceOptions& o) {
    try {
      synth::validate(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  synth::SequenceOptions o = smallDrive(0, 0);
  EXPECT_NE(message(o).find("sequence length 0"), std::string::npos) << message(o);
  o.frames = -3;
  EXPECT_NE(message(o).find("sequence length -3"), std::string::npos) << message(o);
  o.frames = 2;
  o.step = 0.0;
  EXPECT_NE(message(o).find("step"), std::string::npos) << message(o);
  o.step = 7.0;
  EXPECT_NE(message(o).find("step"), std::string::npos) << message(o);
  o.step = 0.8;
  o.frame.beams = 32;
  EXPECT_NE(message(o).find("beams"), std::string::npos) << message(o);
  o.frame.beams = 64;
  o.frame.lidarRangeNoise = -0.01;
  EXPECT_NE(message(o).find("LiDAR range noise"), std::string::npos) << message(o);
  o.frame.lidarRangeNoise = 0.02;
  EXPECT_EQ(message(o), "");
  synth::FrameOptions outOfLane = o.frame;
  outOfLane.rigPosition = {10.0, 3.0, 0.0};  // in the oncoming lane
  EXPECT_THROW(synth::validate(outOfLane), std::invalid_argument);
  outOfLane.rigPosition = {10.0, 0.0, 1.0};  // above the road
  EXPECT_THROW(synth::validate(outOfLane), std::invalid_argument);
  EXPECT_THROW(synth::sequencePose(o, 2), std::invalid_argument);
  EXPECT_THROW(synth::renderSequenceFrame(o, -1), std::invalid_argument);
  EXPECT_THROW(synth::makeStreetScene(1, -5.0), std::invalid_argument);
}

TEST(SynthSequence, PosesAndTimesTextsHaveALinePerFrame) {
  synth::SequenceOptions options = smallDrive(0, 4);
  options.step = 0.5;
  const auto lines = [](const std::string& text) {
    std::vector<std::vector<double>> rows;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      std::istringstream values(line);
      rows.emplace_back();
      for (double v = 0; values >> v;) rows.back().push_back(v);
    }
    return rows;
  };
  const auto poses = lines(synth::kittiPosesText(options));
  const auto times = lines(synth::kittiTimesText(options));
  ASSERT_EQ(poses.size(), 4u);
  ASSERT_EQ(times.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const auto& row = poses[static_cast<std::size_t>(i)];
    ASSERT_EQ(row.size(), 12u);
    const Eigen::Isometry3d pose = synth::sequencePose(options, i);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(row[static_cast<std::size_t>(4 * r + c)], pose.matrix()(r, c), 1e-12);
    }
    ASSERT_EQ(times[static_cast<std::size_t>(i)].size(), 1u);
    EXPECT_NEAR(times[static_cast<std::size_t>(i)][0], 0.1 * i, 1e-9);
  }
}

}  // namespace
}  // namespace lidar_sgm
