// SGMDensification's configuration goes in and out whole (setConfig / getConfig), each
// convenience setter writes its own field of it and nothing else, and a frame runs with it.
#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <pcl/point_types.h>

#include "pcl/pcl_test_helpers.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace {

/// Converts to anything: T{Any, ...} compiles for as many Any as an aggregate T has fields.
struct Any {
  template <typename U>
  operator U() const;  // NOLINT(google-explicit-constructor): only used in unevaluated contexts
};

template <typename T, typename = void, typename... A>
struct BraceConstructible : std::false_type {};
template <typename T, typename... A>
struct BraceConstructible<T, std::void_t<decltype(T{std::declval<A>()...})>, A...> : std::true_type {};

template <typename T, typename... A>
constexpr std::size_t fieldCount() {
  if constexpr (BraceConstructible<T, void, A..., Any>::value) {
    return fieldCount<T, A..., Any>();
  } else {
    return sizeof...(A);
  }
}

// A new field of the configuration is compared below (and gets an entry in the option table,
// config_options.cpp, when a front end sets it).
static_assert(fieldCount<DensifierConfig>() == 14, "DensifierConfig changed: compare the new field here");
static_assert(fieldCount<Parameters>() == 24, "Parameters changed: compare the new field here");
static_assert(fieldCount<geometry::ProjectionOptions>() == 3, "ProjectionOptions changed: compare it here");
static_assert(fieldCount<geometry::OcclusionFilter>() == 6, "OcclusionFilter changed: compare it here");
static_assert(fieldCount<geometry::ReprojectionOptions>() == 4, "ReprojectionOptions changed: compare it here");
static_assert(fieldCount<HiddenLidarOptions>() == 8, "HiddenLidarOptions changed: compare it here");
static_assert(fieldCount<LidarAnchorOptions>() == 7, "LidarAnchorOptions changed: compare it here");

void expectEqual(const Parameters& a, const Parameters& b) {
  EXPECT_EQ(a.minDisparity, b.minDisparity);
  EXPECT_EQ(a.numDisparities, b.numDisparities);
  EXPECT_EQ(a.P1, b.P1);
  EXPECT_EQ(a.P2, b.P2);
  EXPECT_EQ(a.paths, b.paths);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.alphaMode, b.alphaMode);
  EXPECT_EQ(a.sigma, b.sigma);
  EXPECT_EQ(a.lidarCostCap, b.lidarCostCap);
  EXPECT_EQ(a.stereoCostWithoutLidar, b.stereoCostWithoutLidar);
  EXPECT_EQ(a.uniquenessRatio, b.uniquenessRatio);
  EXPECT_EQ(a.lrCheck, b.lrCheck);
  EXPECT_EQ(a.lrCheckWithLidar, b.lrCheckWithLidar);
  EXPECT_EQ(a.disp12MaxDiff, b.disp12MaxDiff);
  EXPECT_EQ(a.lidarCoverageRows, b.lidarCoverageRows);
  EXPECT_EQ(a.gatedSearch, b.gatedSearch);
  EXPECT_EQ(a.gatedSearchMargin, b.gatedSearchMargin);
  EXPECT_EQ(a.gatedSearchRows, b.gatedSearchRows);
  EXPECT_EQ(a.medianSize, b.medianSize);
  EXPECT_EQ(a.subpixel, b.subpixel);
  EXPECT_EQ(a.censusType, b.censusType);
  EXPECT_EQ(a.scale, b.scale);
  EXPECT_EQ(a.threads, b.threads);
  EXPECT_EQ(a.confidence, b.confidence);
}

void expectEqual(const DensifierConfig& a, const DensifierConfig& b) {
  expectEqual(a.matcher, b.matcher);
  EXPECT_EQ(a.backend, b.backend);
  EXPECT_EQ(a.rangeMode, b.rangeMode);
  EXPECT_EQ(a.rangeRule.ignoredPoints, b.rangeRule.ignoredPoints);
  EXPECT_EQ(a.rangeRule.ignoredFraction, b.rangeRule.ignoredFraction);
  EXPECT_EQ(a.rangeRule.marginPx, b.rangeRule.marginPx);
  EXPECT_EQ(a.rangeRule.marginFraction, b.rangeRule.marginFraction);
  EXPECT_EQ(a.rangeRule.minNumDisparities, b.rangeRule.minNumDisparities);
  EXPECT_EQ(a.rangeRule.maxNumDisparities, b.rangeRule.maxNumDisparities);
  EXPECT_EQ(a.projection.minDepth, b.projection.minDepth);
  EXPECT_EQ(a.projection.maxDepth, b.projection.maxDepth);
  EXPECT_EQ(a.projection.occlusion.enabled, b.projection.occlusion.enabled);
  EXPECT_EQ(a.projection.occlusion.halfWidth, b.projection.occlusion.halfWidth);
  EXPECT_EQ(a.projection.occlusion.halfHeight, b.projection.occlusion.halfHeight);
  EXPECT_EQ(a.projection.occlusion.minGap, b.projection.occlusion.minGap);
  EXPECT_EQ(a.projection.occlusion.relativeGap, b.projection.occlusion.relativeGap);
  EXPECT_EQ(a.projection.occlusion.requireEnclosed, b.projection.occlusion.requireEnclosed);
  EXPECT_EQ(a.reprojection.frame, b.reprojection.frame);
  EXPECT_EQ(a.reprojection.maxDepth, b.reprojection.maxDepth);
  EXPECT_EQ(a.reprojection.stride, b.reprojection.stride);
  EXPECT_EQ(a.reprojection.keepOrganized, b.reprojection.keepOrganized);
  EXPECT_EQ(a.cropToScan, b.cropToScan);
  EXPECT_EQ(a.minConfidence, b.minConfidence);
  EXPECT_EQ(a.filters.sky.enabled, b.filters.sky.enabled);
  EXPECT_EQ(a.filters.sky.textureThreshold, b.filters.sky.textureThreshold);
  EXPECT_EQ(a.filters.outliers.enabled, b.filters.outliers.enabled);
  EXPECT_EQ(a.filters.outliers.minNeighbours, b.filters.outliers.minNeighbours);
  EXPECT_EQ(a.lidarConsistency.enabled, b.lidarConsistency.enabled);
  EXPECT_EQ(a.lidarConsistency.costRatio, b.lidarConsistency.costRatio);
  EXPECT_EQ(a.lidarConsistency.marginPerPixel, b.lidarConsistency.marginPerPixel);
  EXPECT_EQ(a.lidarConsistency.searchRadius, b.lidarConsistency.searchRadius);
  EXPECT_EQ(a.lidarConsistency.minDisagreement, b.lidarConsistency.minDisagreement);
  EXPECT_EQ(a.hiddenLidar.enabled, b.hiddenLidar.enabled);
  EXPECT_EQ(a.hiddenLidar.minGap, b.hiddenLidar.minGap);
  EXPECT_EQ(a.hiddenLidar.relativeGap, b.hiddenLidar.relativeGap);
  EXPECT_EQ(a.hiddenLidar.halfWidth, b.hiddenLidar.halfWidth);
  EXPECT_EQ(a.hiddenLidar.supportHalfWidth, b.hiddenLidar.supportHalfWidth);
  EXPECT_EQ(a.hiddenLidar.supportHalfHeight, b.hiddenLidar.supportHalfHeight);
  EXPECT_EQ(a.hiddenLidar.witnessScale, b.hiddenLidar.witnessScale);
  EXPECT_EQ(a.hiddenLidar.witnessMarginRows, b.hiddenLidar.witnessMarginRows);
  EXPECT_EQ(a.lidarAnchor.enabled, b.lidarAnchor.enabled);
  EXPECT_EQ(a.lidarAnchor.maxDisparity, b.lidarAnchor.maxDisparity);
  EXPECT_EQ(a.lidarAnchor.halfWidth, b.lidarAnchor.halfWidth);
  EXPECT_EQ(a.lidarAnchor.halfHeight, b.lidarAnchor.halfHeight);
  EXPECT_EQ(a.lidarAnchor.sigma, b.lidarAnchor.sigma);
  EXPECT_EQ(a.lidarAnchor.agreement, b.lidarAnchor.agreement);
  EXPECT_EQ(a.lidarAnchor.surfaceGap, b.lidarAnchor.surfaceGap);
  EXPECT_EQ(a.pairCheck, b.pairCheck);
  EXPECT_EQ(a.computeCloud, b.computeCloud);
}

using Sgm = SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>;

/// Sets one field through its setter and expects the getter to return it; the expectEqual()
/// calls after each group catch a setter that writes another field.
template <typename Set, typename Get, typename Value>
void check(const char* name, Sgm& sgm, Set set, Get get, Value value) {
  SCOPED_TRACE(name);
  (sgm.*set)(value);
  EXPECT_EQ((sgm.*get)(), value);
}

TEST(SGMDensificationParameters, TheConfigurationGoesInAndComesOutWhole) {
  Sgm sgm;
  expectEqual(sgm.getConfig(), DensifierConfig());  // the shipped default
  DensifierConfig c;
  c.matcher.alpha = 0.25f;
  c.matcher.censusType = CensusType::CenterSymmetric9x7;
  c.backend = Backend::CpuRef;
  c.rangeMode = DisparityRangeMode::Fixed;
  c.rangeRule.maxNumDisparities = 192;
  c.projection.occlusion.halfWidth = 5;
  c.reprojection.stride = 2;
  c.cropToScan = false;
  c.minConfidence = 0.25;
  c.filters.sky.enabled = false;
  c.pairCheck = false;
  sgm.setConfig(c);
  expectEqual(sgm.getConfig(), c);
  // An invalid configuration is refused whole, naming the setting; the object keeps its own.
  DensifierConfig bad = c;
  bad.matcher.paths = 3;
  EXPECT_THROW(sgm.setConfig(bad), std::invalid_argument);
  expectEqual(sgm.getConfig(), c);
  bad = c;
  bad.filters.outliers.minNeighbours = 99;
  try {
    sgm.setConfig(bad);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("minNeighbours"), std::string::npos) << e.what();
  }
  // The option table reads the same configuration from names, as the tools do.
  sgm.setConfig(configFromOptions({{"alpha", "0.25"}, {"census", "cs9x7"}}, {"no_sky_filter"}));
  EXPECT_EQ(sgm.getAlpha(), 0.25f);
  EXPECT_FALSE(sgm.getConfig().filters.sky.enabled);
}

TEST(SGMDensificationParameters, EachConvenienceSetterWritesItsOwnField) {
  Sgm sgm;
  DensifierConfig c;
  // Every value differs from the default, so a setter that writes nothing fails too.
  c.matcher.minDisparity = -8;
  check("minDisparity", sgm, &Sgm::setMinDisparity, &Sgm::getMinDisparity, c.matcher.minDisparity);
  c.matcher.numDisparities = 96;
  check("numDisparities", sgm, &Sgm::setNumDisparities, &Sgm::getNumDisparities, c.matcher.numDisparities);
  c.matcher.P1 = 11;
  check("P1", sgm, &Sgm::setP1, &Sgm::getP1, c.matcher.P1);
  c.matcher.P2 = 123;
  check("P2", sgm, &Sgm::setP2, &Sgm::getP2, c.matcher.P2);
  c.matcher.alpha = 0.25f;
  check("alpha", sgm, &Sgm::setAlpha, &Sgm::getAlpha, c.matcher.alpha);
  c.matcher.scale = 0.5f;
  check("scale", sgm, &Sgm::setScale, &Sgm::getScale, c.matcher.scale);
  c.matcher.threads = 3;
  check("threads", sgm, &Sgm::setNumberOfThreads, &Sgm::getNumberOfThreads, c.matcher.threads);
  c.backend = Backend::CpuRef;
  check("backend", sgm, &Sgm::setBackend, &Sgm::getBackend, c.backend);
  c.rangeMode = DisparityRangeMode::Fixed;
  check("rangeMode", sgm, &Sgm::setDisparityRangeMode, &Sgm::getDisparityRangeMode, c.rangeMode);
  c.minConfidence = 0.5;
  check("minConfidence", sgm, &Sgm::setMinConfidence, &Sgm::getMinConfidence, c.minConfidence);
  c.reprojection.frame = geometry::OutputFrame::Camera;
  check("frame", sgm, &Sgm::setOutputFrame, &Sgm::getOutputFrame, c.reprojection.frame);
  c.reprojection.maxDepth = 33.0;
  check("maxDepth (output)", sgm, &Sgm::setMaxDepth, &Sgm::getMaxDepth, c.reprojection.maxDepth);
  c.reprojection.stride = 2;
  check("stride", sgm, &Sgm::setStride, &Sgm::getStride, c.reprojection.stride);
  c.reprojection.keepOrganized = true;
  check("keepOrganized", sgm, &Sgm::setKeepOrganized, &Sgm::getKeepOrganized, c.reprojection.keepOrganized);
  expectEqual(sgm.getConfig(), c);
  Parameters p = c.matcher;
  p.paths = 8;
  sgm.setParameters(p);
  c.matcher = p;
  expectEqual(sgm.getConfig(), c);
}

TEST(SGMDensificationParameters, TheFrameRunsWithWhatTheSettersSaid) {
  // The getters read the Densifier, so this checks the last step: filter() uses them.
  const geometry::StereoCalibration c = test::pclRig();
  Sgm sgm;
  sgm.setInputCloud(test::wallScan<pcl::PointXYZI>(c));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setBackend(Backend::CpuRef);
  DensifierConfig near = sgm.getConfig();
  near.projection.maxDepth = 3.0;  // the whole 4 m wall is out of range
  sgm.setConfig(near);
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  EXPECT_TRUE(dense.empty());
  EXPECT_NE(sgm.getLastError().find("out of range"), std::string::npos) << sgm.getLastError();
  EXPECT_TRUE(sgm.getProjectedLidar().samples.empty());
  near.projection.maxDepth = 10.0;
  sgm.setConfig(near);
  sgm.setMinDisparity(32);  // the wall's 25 px are below this range...
  const auto wallPixels = [&sgm] {
    std::size_t valid = 0;
    const Image<std::int16_t>& d = sgm.getDisparityImage();
    for (int y = 0; y < d.height(); ++y) {
      for (int x = 0; x < d.width(); ++x) valid += d(x, y) != kInvalidDisparity && d(x, y) < 30 * 16 ? 1 : 0;
    }
    return valid;
  };
  sgm.filter(dense);  // ... but by default the range is the LiDAR's: [0, 25 + 8) -> [0, 48)
  ASSERT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
  EXPECT_TRUE(sgm.getUsedDisparityRange().fromLidar);
  EXPECT_EQ(sgm.getUsedDisparityRange().minDisparity, 0);
  EXPECT_EQ(sgm.getUsedDisparityRange().numDisparities, 48);
  EXPECT_GT(wallPixels(), 0u);
  sgm.setDisparityRangeMode(DisparityRangeMode::Fixed);  // the setters' range
  sgm.filter(dense);
  ASSERT_TRUE(sgm.getLastError().empty()) << sgm.getLastError();
  ASSERT_FALSE(sgm.getDisparityImage().empty());
  EXPECT_EQ(sgm.getUsedBackend(), Backend::CpuRef);
  EXPECT_EQ(sgm.getUsedDisparityRange().describe(), "[32, 96) px (fixed)");
  EXPECT_EQ(wallPixels(), 0u);
  // Depth image: f*b / d on the wall, 0 = none.
  sgm.setMinDisparity(0);
  sgm.filter(dense);
  ASSERT_FALSE(dense.empty()) << sgm.getLastError();
  const Image<float>& depth = sgm.getDepthImage();
  ASSERT_EQ(depth.width(), c.width);
  EXPECT_NEAR(depth(40, 50), test::kWallDepth, 0.02);
  sgm.setMaxDepth(3.5);  // the wall is beyond it: 0 = none
  sgm.filter(dense);
  EXPECT_TRUE(dense.empty());
  EXPECT_EQ(sgm.getDepthImage()(40, 50), 0.0f);
}

}  // namespace
}  // namespace lidar_sgm
