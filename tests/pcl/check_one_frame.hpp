#pragma once
// One frame of the wall for In -> Out through SGMDensification, checked at every pixel: shared by
// the test of the explicitly instantiated types and that of other types through impl/.

#include <gtest/gtest.h>

#include <cmath>

#include <pcl/point_cloud.h>
#include <pcl/type_traits.h>

#include "pcl/pcl_test_helpers.hpp"
#include "lidar_sgm/pcl/sgm_densification.hpp"

namespace lidar_sgm {
namespace test {

/// One frame of the wall for In -> Out, organized, colored by the pixel-coded image; checks
/// geometry, color and intensity at every valid pixel.
template <typename In, typename Out>
inline void checkOneFrame() {
  const geometry::StereoCalibration c = pclRig();
  typename SGMDensification<In, Out>::Ptr sgm(new SGMDensification<In, Out>);
  sgm->setInputCloud(wallScan<In>(c));
  sgm->setCalibration(c);
  sgm->setNumDisparities(64);
  sgm->setColorImage(pixelCodedImage(c.width, c.height));
  sgm->setKeepOrganized(true);
  pcl::PointCloud<Out> dense;
  sgm->filter(dense);
  ASSERT_EQ(dense.size(), static_cast<std::size_t>(c.width * c.height)) << sgm->getLastError();
  int valid = 0;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const Out& p = dense.at(x, y);
      if (!std::isfinite(p.x)) continue;
      ++valid;
      ASSERT_NEAR(cameraDepth(c, p.getVector3fMap()), kWallDepth, 0.02) << x << "," << y;
      if constexpr (pcl::traits::has_color_v<Out>) {
        ASSERT_EQ(p.r, x);
        ASSERT_EQ(p.g, y);
        ASSERT_EQ(p.b, 7);
      }
      if constexpr (pcl::traits::has_intensity_v<Out>) {
        // wallScan put a point at every 2nd column of every 4th row, starting at row 2.
        const bool lidarPixel = x % 2 == 0 && (y - 2) % 4 == 0;
        if (pcl::traits::has_intensity_v<In> && lidarPixel) {
          ASSERT_EQ(p.intensity, wallIntensity(x, y)) << x << "," << y;
        } else {
          ASSERT_NEAR(p.intensity, pixelCodedGray(x, y), 1.0) << x << "," << y;
        }
      }
    }
  }
  EXPECT_GT(valid, c.width * c.height / 2);
}

}  // namespace test
}  // namespace lidar_sgm
