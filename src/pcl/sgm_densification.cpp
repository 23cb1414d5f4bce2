// Explicit instantiations of SGMDensification for the point types ARCHITECTURE.md lists, so
// users of these types do not compile the template body.
#include "lidar_sgm/pcl/impl/sgm_densification.hpp"

template class lidar_sgm::SGMDensification<pcl::PointXYZ, pcl::PointXYZ>;
template class lidar_sgm::SGMDensification<pcl::PointXYZ, pcl::PointXYZRGB>;
template class lidar_sgm::SGMDensification<pcl::PointXYZ, pcl::PointXYZRGBA>;
template class lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZ>;
template class lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGB>;
template class lidar_sgm::SGMDensification<pcl::PointXYZI, pcl::PointXYZRGBA>;
