#pragma once
// The input checks of geometry::reproject and geometry::depthImage (reprojection.cpp), shared
// with the pipeline's fast versions (src/pipeline/fast/reprojection.cpp), so that both refuse the
// same inputs with the same messages.

#include <stdexcept>
#include <string>

#include "lidar_sgm/geometry/reprojection.hpp"

namespace lidar_sgm {
namespace geometry {

inline void checkReprojectionInputs(int width, int height, const StereoCalibration& calibration,
                                    const ReprojectionOptions& options) {
  calibration.validate();
  if (width != calibration.width || height != calibration.height) {
    throw std::invalid_argument("reproject: the disparity image is " + std::to_string(width) + "x" +
                                std::to_string(height) + " but the calibration is " +
                                std::to_string(calibration.width) + "x" + std::to_string(calibration.height));
  }
  if (options.stride < 1) throw std::invalid_argument("reproject: stride must be >= 1");
  if (!(options.maxDepth > 0.0)) throw std::invalid_argument("reproject: maxDepth must be positive [m]");
}

inline void checkDepthImageInputs(double focalBaseline, double maxDepth) {
  if (!(focalBaseline > 0.0)) throw std::invalid_argument("depthImage: focal length * baseline must be positive");
  if (!(maxDepth > 0.0)) throw std::invalid_argument("depthImage: maxDepth must be positive [m]");
}

}  // namespace geometry
}  // namespace lidar_sgm
