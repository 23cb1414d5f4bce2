// One SGMDensification reused for frame after frame (a worker of lidar_sgm_batch, a PCL user's
// loop) gives each frame the cloud a fresh object gives it: a frame's images belong to that
// frame, whatever came before it and in whichever order the setters were called.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "common/synthetic_stereo.hpp"
#include "lidar_sgm/pcl/point_types.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"
#include "pcl/pcl_test_helpers.hpp"

namespace lidar_sgm {
namespace {

using PointOut = PointXYZRGBConfidence;
using Densification = SGMDensification<pcl::PointXYZI, PointOut>;

pcl::PointCloud<pcl::RGB> toRgb(const Image<std::uint8_t>& gray, std::uint8_t blue) {
  pcl::PointCloud<pcl::RGB> image(static_cast<std::uint32_t>(gray.width()), static_cast<std::uint32_t>(gray.height()));
  for (int y = 0; y < gray.height(); ++y) {
    for (int x = 0; x < gray.width(); ++x) {
      image.at(x, y).r = image.at(x, y).g = gray(x, y);
      image.at(x, y).b = blue;
    }
  }
  return image;
}

/// What one frame is given: a scan, and maybe a pair (as PCL images or gray views) and a color
/// image.
struct FrameInputs {
  std::string name;
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan;
  enum class Pair { None, Color, Gray } pair = Pair::None;
  test::SyntheticStereo stereo;
  bool colorImage = false;
};

std::vector<FrameInputs> frames() {
  const geometry::StereoCalibration c = test::pclRig();
  std::vector<FrameInputs> f(4);
  f[0].name = "color pair";
  f[0].scan = test::wallScan<pcl::PointXYZI>(c);
  f[0].pair = FrameInputs::Pair::Color;
  f[0].stereo = test::makeStereo(c.width, c.height, [](double, double) { return 25.0; });
  f[1].name = "scan and color image";
  f[1].scan = test::wallScan<pcl::PointXYZI>(c, true);
  f[1].colorImage = true;
  f[2].name = "scan only";
  f[2].scan = test::wallScan<pcl::PointXYZI>(c);
  f[3].name = "gray pair";
  f[3].scan = test::wallScan<pcl::PointXYZI>(c, true);
  f[3].pair = FrameInputs::Pair::Gray;
  f[3].stereo = test::makeStereo(c.width, c.height, [](double x, double) { return x < 80 ? 25.0 : 20.0; }, 0, 11);
  return f;
}

/// Gives `sgm` the frame, the images before or after the scan, and densifies it.
pcl::PointCloud<PointOut> densify(Densification& sgm, const FrameInputs& frame, bool imagesFirst) {
  const auto images = [&] {
    if (frame.pair == FrameInputs::Pair::Color) {
      sgm.setStereoPair(toRgb(frame.stereo.left, 3), toRgb(frame.stereo.right, 5));
    } else if (frame.pair == FrameInputs::Pair::Gray) {
      sgm.setStereoPair(frame.stereo.left.view(), frame.stereo.right.view());
    }
    if (frame.colorImage) sgm.setColorImage(test::pixelCodedImage(160, 96));
  };
  if (imagesFirst) images();
  sgm.setInputCloud(frame.scan);
  if (!imagesFirst) images();
  pcl::PointCloud<PointOut> out;
  sgm.filter(out);
  EXPECT_TRUE(sgm.getLastError().empty()) << frame.name << ": " << sgm.getLastError();
  return out;
}

void configure(Densification& sgm) {
  sgm.setCalibration(test::pclRig());
  sgm.setDisparityRangeMode(DisparityRangeMode::Fixed);
  sgm.setNumDisparities(64);
}

bool sameBytes(const pcl::PointCloud<PointOut>& a, const pcl::PointCloud<PointOut>& b) {
  if (a.size() != b.size() || a.width != b.width || a.height != b.height) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Field by field: NaN confidences compare equal by bits.
    if (std::memcmp(a[i].data, b[i].data, sizeof(a[i].data)) != 0 || a[i].rgba != b[i].rgba ||
        std::memcmp(&a[i].confidence, &b[i].confidence, sizeof(float)) != 0) {
      return false;
    }
  }
  return true;
}

TEST(SGMDensificationFrames, AReusedObjectGivesEveryFrameAFreshObjectsCloudAfterEveryOtherFrame) {
  const std::vector<FrameInputs> inputs = frames();
  std::vector<pcl::PointCloud<PointOut>> fresh;
  for (const FrameInputs& frame : inputs) {
    Densification sgm;
    configure(sgm);
    fresh.push_back(densify(sgm, frame, false));
    ASSERT_FALSE(fresh.back().empty()) << frame.name;
  }
  // The four frames differ, so a frame that got another's image would show it.
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    for (std::size_t j = i + 1; j < fresh.size(); ++j) EXPECT_FALSE(sameBytes(fresh[i], fresh[j])) << i << " " << j;
  }
  // Every frame after every other one: the 12 ordered pairs of the 4 frames, in one sequence.
  const std::vector<int> sequence{0, 1, 2, 3, 0, 2, 1, 3, 2, 0, 3, 1, 0};
  for (const bool imagesFirst : {false, true}) {
    Densification sgm;
    configure(sgm);
    int previous = -1;
    for (const int f : sequence) {
      // Each frame twice: a parameter sweep's filter() again keeps the frame.
      for (int again = 0; again < 2; ++again) {
        pcl::PointCloud<PointOut> out;
        if (again == 0) {
          out = densify(sgm, inputs[f], imagesFirst);
        } else {
          sgm.filter(out);
        }
        EXPECT_TRUE(sameBytes(out, fresh[f])) << inputs[f].name << " after " << (previous < 0 ? "nothing" : inputs[previous].name)
                                              << (imagesFirst ? ", images given before the scan" : "")
                                              << (again ? ", filtered again" : "");
      }
      previous = f;
    }
  }
}

TEST(SGMDensificationFrames, ClearingThePairOrGivingItAgainIsTheFramesOwnChoice) {
  const std::vector<FrameInputs> inputs = frames();
  Densification sgm;
    configure(sgm);
  densify(sgm, inputs[0], false);
  EXPECT_EQ(sgm.getLastMode(), MatchMode::Fused);
  // The same pair given again before the next scan is that frame's.
  sgm.setStereoPair(toRgb(inputs[0].stereo.left, 3), toRgb(inputs[0].stereo.right, 5));
  sgm.setInputCloud(inputs[2].scan);
  pcl::PointCloud<PointOut> out;
  sgm.filter(out);
  EXPECT_EQ(sgm.getLastMode(), MatchMode::Fused);
  // Not given again: LiDAR-only, uncolored.
  sgm.setInputCloud(inputs[2].scan);
  sgm.filter(out);
  EXPECT_EQ(sgm.getLastMode(), MatchMode::LidarOnly);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out[out.size() / 2].rgba, PointOut().rgba);
  // An unusable pair given to one frame is that frame's error, not the next one's.
  sgm.setStereoPair(pcl::PointCloud<pcl::RGB>(), pcl::PointCloud<pcl::RGB>());
  sgm.filter(out);
  EXPECT_NE(sgm.getLastError().find("organized"), std::string::npos) << sgm.getLastError();
  sgm.setInputCloud(inputs[2].scan);
  sgm.filter(out);
  EXPECT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
  EXPECT_FALSE(out.empty());
}

}  // namespace
}  // namespace lidar_sgm
