#pragma once
/// @file point_types.hpp  PCL point types with the per-point confidence of LiDAR-SGM
/// (core/confidence.hpp), registered with PCL so that its io writes the `confidence` field to
/// PCD and PLY (read by PCL, CloudCompare (as a scalar field) and Open3D's tensor io).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

namespace lidar_sgm {

/// x, y, z and the confidence in [0, 1]: about the probability that the point is correct
/// (its disparity within 3 px or 5 % of the truth).
struct EIGEN_ALIGN16 PointXYZConfidence {
  PCL_ADD_POINT4D;
  float confidence;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/// x, y, z, rgb and the confidence in [0, 1].
struct EIGEN_ALIGN16 PointXYZRGBConfidence {
  PCL_ADD_POINT4D;
  PCL_ADD_RGB;
  float confidence;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace lidar_sgm

POINT_CLOUD_REGISTER_POINT_STRUCT(lidar_sgm::PointXYZConfidence,
                                  (float, x, x)(float, y, y)(float, z, z)(float, confidence, confidence))
POINT_CLOUD_REGISTER_POINT_STRUCT(lidar_sgm::PointXYZRGBConfidence,
                                  (float, x, x)(float, y, y)(float, z, z)(float, rgb, rgb)(float, confidence,
                                                                                           confidence))
