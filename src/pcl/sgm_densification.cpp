// Explicit instantiations of SGMDensification, with PCL's macros as its own filters do, so that
// users of these types do not compile the template body: XYZ / XYZI / XYZRGB / XYZRGBA in, and
// XYZ / XYZRGB / XYZRGBA / XYZI out (LIDAR_SGM_PCL_{INPUT,OUTPUT}_POINT_TYPES), and the confidence
// types: about half a second of compilation each (g++ 12, -O3), in every build; any other type
// goes through impl/.
#include <pcl/impl/instantiate.hpp>
#include <pcl/point_types.h>

#include "lidar_sgm/pcl/impl/sgm_densification.hpp"

PCL_INSTANTIATE_PRODUCT(SGMDensification, (LIDAR_SGM_PCL_INPUT_POINT_TYPES)(LIDAR_SGM_PCL_OUTPUT_POINT_TYPES))
PCL_INSTANTIATE_PRODUCT(SGMDensification,
                        (LIDAR_SGM_PCL_CONFIDENCE_INPUT_POINT_TYPES)(LIDAR_SGM_PCL_CONFIDENCE_OUTPUT_POINT_TYPES))
