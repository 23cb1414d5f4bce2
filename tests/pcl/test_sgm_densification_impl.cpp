// Point types outside the explicit instantiations, as a user's own LiDAR driver type or any other
// PCL type with x, y, z is used: PCL's convention for its own classes, PCL_NO_PRECOMPILE defined
// before any PCL header, which brings in the template bodies (pcl::PCLBase's and ours).
#define PCL_NO_PRECOMPILE
#include <gtest/gtest.h>

#include <cstdint>

#include <boost/preprocessor/seq/size.hpp>
#include <pcl/common/io.h>
#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include "pcl/check_one_frame.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace driver {
/// A driver's own point, laid out as Ouster's ROS driver does: intensity, time, reflectivity, ring.
struct EIGEN_ALIGN16 LidarPoint {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint32_t t;
  std::uint16_t reflectivity;
  std::uint16_t ring;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};
}  // namespace driver

POINT_CLOUD_REGISTER_POINT_STRUCT(driver::LidarPoint,
                                  (float, x, x)(float, y, y)(float, z, z)(float, intensity, intensity)(
                                      std::uint32_t, t, t)(std::uint16_t, reflectivity, reflectivity)(std::uint16_t,
                                                                                                     ring, ring))

namespace lidar_sgm {
namespace {

using test::checkOneFrame;

TEST(SGMDensificationOtherTypes, ADriversOwnPointTypeKeepsItsIntensity) {
  checkOneFrame<driver::LidarPoint, pcl::PointXYZI>();
  checkOneFrame<driver::LidarPoint, pcl::PointXYZRGB>();
}

// Every other PCL type with x, y, z (PCL_XYZ_POINT_TYPES less the instantiated inputs), colored;
// and, where the type has an intensity, into an XYZI output that keeps it.
template <typename In>
class SGMDensificationOtherTypes : public ::testing::Test {};
using OtherPclTypes =
    ::testing::Types<pcl::PointXYZL, pcl::PointXYZRGBL, pcl::PointXYZLAB, pcl::PointXYZHSV, pcl::InterestPoint,
                     pcl::PointNormal, pcl::PointXYZRGBNormal, pcl::PointXYZINormal, pcl::PointXYZLNormal,
                     pcl::PointWithRange, pcl::PointWithViewpoint, pcl::PointWithScale, pcl::PointSurfel,
                     pcl::PointDEM>;
// A PCL that adds a type to PCL_XYZ_POINT_TYPES makes this fail: add it above.
static_assert(BOOST_PP_SEQ_SIZE(PCL_XYZ_POINT_TYPES) ==
                  14 + BOOST_PP_SEQ_SIZE(LIDAR_SGM_PCL_INPUT_POINT_TYPES),
              "OtherPclTypes must list every PCL_XYZ_POINT_TYPES type that is not instantiated");
TYPED_TEST_SUITE(SGMDensificationOtherTypes, OtherPclTypes);

TYPED_TEST(SGMDensificationOtherTypes, DensifiesColorsAndCarriesIntensity) {
  checkOneFrame<TypeParam, pcl::PointXYZRGB>();
  if constexpr (pcl::traits::has_intensity_v<TypeParam>) checkOneFrame<TypeParam, pcl::PointXYZI>();
}

}  // namespace
}  // namespace lidar_sgm
