// Every explicitly instantiated SGMDensification<In, Out> (linking proves the instantiation
// exists: this file includes no template body), and the intensity rule of an XYZI output.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include <boost/preprocessor/seq/enum.hpp>
#include <pcl/common/io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/type_traits.h>

#include "pcl/check_one_frame.hpp"
#include "pcl/pcl_test_helpers.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace {

using test::checkOneFrame;
using test::pclRig;
using test::wallIntensity;
using test::wallScan;

template <typename In>
class SGMDensificationTypes : public ::testing::Test {};
// The same sequence src/pcl/sgm_densification.cpp instantiates.
using InputTypes = ::testing::Types<BOOST_PP_SEQ_ENUM(LIDAR_SGM_PCL_INPUT_POINT_TYPES)>;
using OutputTypes = std::tuple<BOOST_PP_SEQ_ENUM(LIDAR_SGM_PCL_OUTPUT_POINT_TYPES)>;
TYPED_TEST_SUITE(SGMDensificationTypes, InputTypes);

template <typename In, typename... Out>
void checkEachOutput(std::tuple<Out...>*) {
  (
      [] {
        SCOPED_TRACE(pcl::getFieldsList(pcl::PointCloud<Out>()));
        checkOneFrame<In, Out>();
      }(),
      ...);
}

TYPED_TEST(SGMDensificationTypes, EveryOutputTypeDensifiesColorsAndCarriesIntensity) {
  checkEachOutput<TypeParam>(static_cast<OutputTypes*>(nullptr));
}

TEST(SGMDensificationIntensity, FromTheImageWhereNoPointElseNaN) {
  const geometry::StereoCalibration c = pclRig();
  SGMDensification<pcl::PointXYZI, pcl::PointXYZI> sgm;
  sgm.setInputCloud(wallScan<pcl::PointXYZI>(c));
  sgm.setCalibration(c);
  sgm.setNumDisparities(64);
  sgm.setKeepOrganized(true);
  pcl::PointCloud<pcl::PointXYZI> dense;
  sgm.filter(dense);  // no image at all
  ASSERT_EQ(dense.size(), static_cast<std::size_t>(c.width * c.height)) << sgm.getLastError();
  int lidar = 0;
  int none = 0;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      if (!std::isfinite(dense.at(x, y).x)) continue;
      const float intensity = dense.at(x, y).intensity;
      if (x % 2 == 0 && (y - 2) % 4 == 0) {
        ASSERT_EQ(intensity, wallIntensity(x, y));
        ++lidar;
      } else {
        ASSERT_TRUE(std::isnan(intensity)) << x << "," << y << ": " << intensity;
        ++none;
      }
    }
  }
  EXPECT_GT(lidar, 1000);
  EXPECT_GT(none, 5000);

  // A gray 16-bit pair gives its high byte where there is no point.
  Image<std::uint16_t> left(c.width, c.height, 0x4A11), right(c.width, c.height, 0x4A11);
  sgm.setStereoPair(left.view(), right.view());
  sgm.filter(dense);
  ASSERT_FALSE(dense.empty()) << sgm.getLastError();
  EXPECT_EQ(dense.at(1, 2).intensity, static_cast<float>(0x4A));
  EXPECT_EQ(dense.at(0, 2).intensity, wallIntensity(0, 2));
}

}  // namespace
}  // namespace lidar_sgm
