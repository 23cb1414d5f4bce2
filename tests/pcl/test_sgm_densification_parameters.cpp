// Every setter of SGMDensification writes its own field of the Densifier's options (read back
// through getParameters() & co., which return the Densifier's), and nothing else; and every
// field has a setter (the field counts below fail when a field is added).
#include <gtest/gtest.h>

#include <cstddef>
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

// A new field needs a setter/getter pair in SGMDensification and a line in the test below.
static_assert(fieldCount<Parameters>() == 21, "Parameters changed: add the setter and test it here");
static_assert(fieldCount<geometry::ProjectionOptions>() == 3, "ProjectionOptions changed: add the setter");
static_assert(fieldCount<geometry::OcclusionFilter>() == 6, "OcclusionFilter changed: add the setter");
static_assert(fieldCount<geometry::ReprojectionOptions>() == 4, "ReprojectionOptions changed: add the setter");

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
  EXPECT_EQ(a.medianSize, b.medianSize);
  EXPECT_EQ(a.subpixel, b.subpixel);
  EXPECT_EQ(a.censusType, b.censusType);
  EXPECT_EQ(a.scale, b.scale);
  EXPECT_EQ(a.threads, b.threads);
  EXPECT_EQ(a.confidence, b.confidence);
}

void expectEqual(const geometry::ProjectionOptions& a, const geometry::ProjectionOptions& b) {
  EXPECT_EQ(a.minDepth, b.minDepth);
  EXPECT_EQ(a.maxDepth, b.maxDepth);
  EXPECT_EQ(a.occlusion.enabled, b.occlusion.enabled);
  EXPECT_EQ(a.occlusion.halfWidth, b.occlusion.halfWidth);
  EXPECT_EQ(a.occlusion.halfHeight, b.occlusion.halfHeight);
  EXPECT_EQ(a.occlusion.minGap, b.occlusion.minGap);
  EXPECT_EQ(a.occlusion.relativeGap, b.occlusion.relativeGap);
  EXPECT_EQ(a.occlusion.requireEnclosed, b.occlusion.requireEnclosed);
}

void expectEqual(const geometry::ReprojectionOptions& a, const geometry::ReprojectionOptions& b) {
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.maxDepth, b.maxDepth);
  EXPECT_EQ(a.stride, b.stride);
  EXPECT_EQ(a.keepOrganized, b.keepOrganized);
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

TEST(SGMDensificationParameters, EverySetterReachesTheDensifiersOwnField) {
  Sgm sgm;
  Parameters p;  // defaults, as the class starts with
  expectEqual(sgm.getParameters(), p);
  // Every value differs from the default, so a setter that writes nothing fails too.
  p.minDisparity = -8;
  check("minDisparity", sgm, &Sgm::setMinDisparity, &Sgm::getMinDisparity, p.minDisparity);
  p.numDisparities = 96;
  check("numDisparities", sgm, &Sgm::setNumDisparities, &Sgm::getNumDisparities, p.numDisparities);
  p.P1 = 11;
  check("P1", sgm, &Sgm::setP1, &Sgm::getP1, p.P1);
  p.P2 = 123;
  check("P2", sgm, &Sgm::setP2, &Sgm::getP2, p.P2);
  p.paths = 8;
  check("paths", sgm, &Sgm::setPaths, &Sgm::getPaths, p.paths);
  p.alpha = 0.25f;
  check("alpha", sgm, &Sgm::setAlpha, &Sgm::getAlpha, p.alpha);
  p.alphaMode = AlphaMode::Adaptive;
  check("alphaMode", sgm, &Sgm::setAlphaMode, &Sgm::getAlphaMode, p.alphaMode);
  p.sigma = 3.5f;
  check("sigma", sgm, &Sgm::setSigma, &Sgm::getSigma, p.sigma);
  p.lidarCostCap = 40;
  check("lidarCostCap", sgm, &Sgm::setLidarCostCap, &Sgm::getLidarCostCap, p.lidarCostCap);
  p.stereoCostWithoutLidar = !p.stereoCostWithoutLidar;
  check("stereoCostWithoutLidar", sgm, &Sgm::setStereoCostWithoutLidar, &Sgm::getStereoCostWithoutLidar,
        p.stereoCostWithoutLidar);
  p.uniquenessRatio = 15;
  check("uniquenessRatio", sgm, &Sgm::setUniquenessRatio, &Sgm::getUniquenessRatio, p.uniquenessRatio);
  p.lrCheck = !p.lrCheck;
  check("lrCheck", sgm, &Sgm::setLRCheck, &Sgm::getLRCheck, p.lrCheck);
  p.lrCheckWithLidar = !p.lrCheckWithLidar;
  check("lrCheckWithLidar", sgm, &Sgm::setLRCheckWithLidar, &Sgm::getLRCheckWithLidar, p.lrCheckWithLidar);
  p.disp12MaxDiff = 3;
  check("disp12MaxDiff", sgm, &Sgm::setDisp12MaxDiff, &Sgm::getDisp12MaxDiff, p.disp12MaxDiff);
  p.lidarCoverageRows = 9;
  check("lidarCoverageRows", sgm, &Sgm::setLidarCoverageRows, &Sgm::getLidarCoverageRows, p.lidarCoverageRows);
  p.medianSize = 3;
  check("medianSize", sgm, &Sgm::setMedianSize, &Sgm::getMedianSize, p.medianSize);
  p.subpixel = !p.subpixel;
  check("subpixel", sgm, &Sgm::setSubpixel, &Sgm::getSubpixel, p.subpixel);
  p.censusType = CensusType::CenterSymmetric9x7;
  check("censusType", sgm, &Sgm::setCensusType, &Sgm::getCensusType, p.censusType);
  p.scale = 0.5f;
  check("scale", sgm, &Sgm::setScale, &Sgm::getScale, p.scale);
  p.threads = 3;
  check("threads", sgm, &Sgm::setNumberOfThreads, &Sgm::getNumberOfThreads, p.threads);
  p.confidence = !p.confidence;
  check("confidence", sgm, &Sgm::setComputeConfidence, &Sgm::getComputeConfidence, p.confidence);
  expectEqual(sgm.getParameters(), p);

  geometry::ProjectionOptions o;
  expectEqual(sgm.getProjectionOptions(), o);
  o.minDepth = 1.25;
  check("minDepth", sgm, &Sgm::setMinPointDepth, &Sgm::getMinPointDepth, o.minDepth);
  o.maxDepth = 70.0;
  check("maxDepth (projection)", sgm, &Sgm::setMaxPointDepth, &Sgm::getMaxPointDepth, o.maxDepth);
  o.occlusion.enabled = !o.occlusion.enabled;
  check("occlusion.enabled", sgm, &Sgm::setOcclusionFilter, &Sgm::getOcclusionFilter, o.occlusion.enabled);
  o.occlusion.halfWidth = 5;
  check("occlusion.halfWidth", sgm, &Sgm::setOcclusionHalfWidth, &Sgm::getOcclusionHalfWidth, o.occlusion.halfWidth);
  o.occlusion.halfHeight = 7;
  check("occlusion.halfHeight", sgm, &Sgm::setOcclusionHalfHeight, &Sgm::getOcclusionHalfHeight,
        o.occlusion.halfHeight);
  o.occlusion.minGap = 3.5;
  check("occlusion.minGap", sgm, &Sgm::setOcclusionMinGap, &Sgm::getOcclusionMinGap, o.occlusion.minGap);
  o.occlusion.relativeGap = 0.3;
  check("occlusion.relativeGap", sgm, &Sgm::setOcclusionRelativeGap, &Sgm::getOcclusionRelativeGap,
        o.occlusion.relativeGap);
  o.occlusion.requireEnclosed = !o.occlusion.requireEnclosed;
  check("occlusion.requireEnclosed", sgm, &Sgm::setOcclusionRequireEnclosed, &Sgm::getOcclusionRequireEnclosed,
        o.occlusion.requireEnclosed);
  expectEqual(sgm.getProjectionOptions(), o);

  geometry::ReprojectionOptions r;
  expectEqual(sgm.getReprojectionOptions(), r);
  r.frame = geometry::OutputFrame::Camera;
  check("frame", sgm, &Sgm::setOutputFrame, &Sgm::getOutputFrame, r.frame);
  r.maxDepth = 33.0;
  check("maxDepth (output)", sgm, &Sgm::setMaxDepth, &Sgm::getMaxDepth, r.maxDepth);
  r.stride = 2;
  check("stride", sgm, &Sgm::setStride, &Sgm::getStride, r.stride);
  r.keepOrganized = !r.keepOrganized;
  check("keepOrganized", sgm, &Sgm::setKeepOrganized, &Sgm::getKeepOrganized, r.keepOrganized);
  expectEqual(sgm.getReprojectionOptions(), r);
  // The parameters were not touched by the option setters.
  expectEqual(sgm.getParameters(), p);

  EXPECT_EQ(sgm.getBackend(), Backend::Auto);
  sgm.setBackend(Backend::CpuRef);
  EXPECT_EQ(sgm.getBackend(), Backend::CpuRef);
  EXPECT_TRUE(sgm.getCropToScan());
  sgm.setCropToScan(false);
  EXPECT_FALSE(sgm.getCropToScan());
  EXPECT_EQ(sgm.getDisparityRangeMode(), DisparityRangeMode::FromLidar);
  sgm.setDisparityRangeMode(DisparityRangeMode::Fixed);
  EXPECT_EQ(sgm.getDisparityRangeMode(), DisparityRangeMode::Fixed);
  geometry::DisparityRangeRule rule;
  rule.maxNumDisparities = 192;
  sgm.setDisparityRangeRule(rule);
  EXPECT_EQ(sgm.getDisparityRangeRule().maxNumDisparities, 192);
  expectEqual(sgm.getParameters(), p);

  // The output filters: both on by default, each switch touches only its own filter.
  EXPECT_TRUE(sgm.getSkyFilter());
  EXPECT_TRUE(sgm.getOutlierFilter());
  sgm.setSkyFilter(false);
  EXPECT_FALSE(sgm.getSkyFilter());
  EXPECT_TRUE(sgm.getOutlierFilter());
  sgm.setOutlierFilter(false);
  EXPECT_FALSE(sgm.getOutlierFilter());
  OutputFilterOptions filters;
  filters.outliers.minNeighbours = 7;
  filters.sky.textureThreshold = 2.5;
  sgm.setOutputFilters(filters);
  EXPECT_TRUE(sgm.getSkyFilter());
  EXPECT_EQ(sgm.getOutputFilters().outliers.minNeighbours, 7);
  EXPECT_EQ(sgm.getOutputFilters().sky.textureThreshold, 2.5);
}

TEST(SGMDensificationParameters, TheFrameRunsWithWhatTheSettersSaid) {
  // The getters read the Densifier, so this checks the last step: filter() uses them.
  const geometry::StereoCalibration c = test::pclRig();
  Sgm sgm;
  sgm.setInputCloud(test::wallScan<pcl::PointXYZI>(c));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setBackend(Backend::CpuRef);
  sgm.setMaxPointDepth(3.0);  // the whole 4 m wall is out of range
  pcl::PointCloud<pcl::PointXYZRGB> dense;
  sgm.filter(dense);
  EXPECT_TRUE(dense.empty());
  EXPECT_NE(sgm.getLastError().find("out of range"), std::string::npos) << sgm.getLastError();
  EXPECT_TRUE(sgm.getProjectedLidar().samples.empty());
  sgm.setMaxPointDepth(10.0);
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
