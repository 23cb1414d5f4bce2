#include "lidar_sgm/core/parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <algorithm>

namespace lidar_sgm {
namespace {

std::string rangeError(const char* name, double value, const std::string& allowed) {
  std::ostringstream os;
  os << "invalid parameter " << name << " = " << value << ": must be " << allowed;
  return os.str();
}

}  // namespace

std::string validationError(const Parameters& p) {
  if (p.numDisparities < 16 || p.numDisparities > 512 || p.numDisparities % 16 != 0) {
    return rangeError("numDisparities", p.numDisparities, "a multiple of 16 in [16, 512]");
  }
  if (p.minDisparity < -512 || p.minDisparity > 512) {
    return rangeError("minDisparity", p.minDisparity, "in [-512, 512]");
  }
  if (p.P1 < 0 || p.P1 > 3999) return rangeError("P1", p.P1, "in [0, 3999]");
  if (p.P2 <= p.P1 || p.P2 > 4000) {
    return rangeError("P2", p.P2, "greater than P1 (" + std::to_string(p.P1) + ") and at most 4000");
  }
  if (p.paths != 4 && p.paths != 8) return rangeError("paths", p.paths, "4 or 8");
  if (!std::isfinite(p.alpha) || p.alpha < 0.0f || p.alpha > 1.0f) {
    return rangeError("alpha", p.alpha, "in [0, 1]");
  }
  if (p.alphaMode != AlphaMode::Fixed && p.alphaMode != AlphaMode::Adaptive) {
    return rangeError("alphaMode", static_cast<int>(p.alphaMode), "Fixed (0) or Adaptive (1)");
  }
  if (!std::isfinite(p.sigma) || p.sigma < 0.1f || p.sigma > 100.0f) {
    return rangeError("sigma", p.sigma, "in [0.1, 100] px");
  }
  if (p.lidarCostCap < 1 || p.lidarCostCap > 255) {
    return rangeError("lidarCostCap", p.lidarCostCap, "in [1, 255]");
  }
  if (p.uniquenessRatio < 0 || p.uniquenessRatio > 99) {
    return rangeError("uniquenessRatio", p.uniquenessRatio, "in [0, 99] %");
  }
  if (p.disp12MaxDiff < 0 || p.disp12MaxDiff > p.numDisparities) {
    return rangeError("disp12MaxDiff", p.disp12MaxDiff,
                      "in [0, numDisparities (" + std::to_string(p.numDisparities) + ")]");
  }
  if (p.lidarCoverageRows < 1 || p.lidarCoverageRows > 64) {
    return rangeError("lidarCoverageRows", p.lidarCoverageRows, "in [1, 64]");
  }
  if (p.gatedSearchMargin < 0 || p.gatedSearchMargin > 512) {
    return rangeError("gatedSearchMargin", p.gatedSearchMargin, "in [0, 512] px");
  }
  if (p.gatedSearchRows < 0 || p.gatedSearchRows > 64) {
    return rangeError("gatedSearchRows", p.gatedSearchRows, "in [0, 64]");
  }
  if (p.medianSize != 0 && p.medianSize != 3 && p.medianSize != 5) {
    return rangeError("medianSize", p.medianSize, "0 (off), 3 or 5");
  }
  if (!(p.scale == 1.0f || p.scale == 0.5f)) {
    return rangeError("scale", p.scale, "1 (full resolution) or 0.5 (half scale)");
  }
  if (p.scale == 0.5f && p.numDisparities % 32 != 0) {
    return rangeError("numDisparities", p.numDisparities,
                      "a multiple of 32 at scale 0.5 (half of it, a multiple of 16, is searched)");
  }
  if (p.scale == 0.5f && p.minDisparity % 2 != 0) {
    return rangeError("minDisparity", p.minDisparity, "even at scale 0.5 (half of it is searched)");
  }
  if (p.threads < 0 || p.threads > 256) {
    return rangeError("threads", p.threads, "in [0, 256] (0 = hardware threads)");
  }
  return {};
}

int effectiveThreads(const Parameters& params) {
  if (params.threads > 0) return params.threads;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(std::min(hardware, 256u));
}

void validate(const Parameters& params) {
  const std::string error = validationError(params);
  if (!error.empty()) throw std::invalid_argument(error);
}

std::string toString(CensusType type) {
  return type == CensusType::Census9x7 ? "census9x7" : "cs_census9x7";
}

std::string toString(AlphaMode mode) { return mode == AlphaMode::Adaptive ? "adaptive" : "fixed"; }

AlphaMode alphaModeFromString(const std::string& text) {
  if (text == "fixed") return AlphaMode::Fixed;
  if (text == "adaptive") return AlphaMode::Adaptive;
  throw std::invalid_argument("alpha mode '" + text + "': must be fixed or adaptive");
}

}  // namespace lidar_sgm
