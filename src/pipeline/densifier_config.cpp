#include "lidar_sgm/pipeline/densifier_config.hpp"

#include <cmath>
#include <stdexcept>

namespace lidar_sgm {

std::string toString(DisparityRangeMode mode) { return mode == DisparityRangeMode::Fixed ? "fixed" : "lidar"; }

std::string validationError(const DensifierConfig& c) {
  std::string error = validationError(c.matcher);
  if (!error.empty()) return error;
  error = geometry::validationError(c.rangeRule);
  if (!error.empty()) return error;
  if (!(c.minConfidence >= 0.0 && c.minConfidence <= 1.0)) {
    return "invalid parameter minConfidence = " + std::to_string(c.minConfidence) + ": must be in [0, 1]";
  }
  if (c.minConfidence > 0.0 && !c.matcher.confidence) {
    return "invalid parameter minConfidence = " + std::to_string(c.minConfidence) +
           ": a minimum confidence needs the confidence, which is off (Parameters::confidence, -no_confidence)";
  }
  if (c.reprojection.stride < 1) {
    return "invalid parameter stride = " + std::to_string(c.reprojection.stride) + ": must be >= 1";
  }
  if (!(c.reprojection.maxDepth > 0.0)) {
    return "invalid parameter maxDepth = " + std::to_string(c.reprojection.maxDepth) +
           ": must be positive [m] (infinity keeps all)";
  }
  // The projection's and the filters' own checks throw; their messages name the field.
  try {
    geometry::validate(c.projection);
    validate(c.filters.sky);
    validate(c.filters.outliers);
    validate(c.lidarConsistency);
    validate(c.hiddenLidar);
    validate(c.lidarAnchor);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

void validate(const DensifierConfig& config) {
  const std::string error = validationError(config);
  if (!error.empty()) throw std::invalid_argument(error);
}

}  // namespace lidar_sgm
