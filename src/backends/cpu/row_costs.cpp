// The matching cost C of a row's pixels, computed on the fly in the sweep up: C_L from the points
// around each pixel, C_S (or Triple-SGM's C_S3) from the census images, fused by Eq. 5 while the
// pixel's costs are still in the L1 cache. No cost volume but C itself is ever stored, and no
// census image of the pair: each thread computes the census of its part of the row where it needs
// it (the left pixels it costs, the right pixels they can match, and those as planes): ~13 MB
// less memory a KITTI frame.
#include <algorithm>
#include <cstring>

#include "backends/cpu/cpu_kernels.hpp"
#include "backends/cpu/cpu_matcher.hpp"

namespace lidar_sgm {
namespace cpu {

void CpuMatcher::censusRows(const Frame& f, int y, int x0, int x1, Worker& w) {
  const CensusType type = f.plan.params.censusType;
  const int W = f.plan.width;
  // The right pixels that pixels x0 .. x1-1 can match (census_cost.cpp ignores all others).
  const int xr0 = std::clamp(x0 - f.plan.minDisparity - f.plan.D + 1, 0, W);
  const int xr1 = std::clamp(x1 - f.plan.minDisparity, xr0, W);
  if (!f.left.gray8.empty()) {
    censusTransformRow(f.left.gray8, type, y, x0, x1, w.leftCensus.data());
    censusTransformRow(f.right.gray8, type, y, xr0, xr1, w.rightCensus.data());
  } else {
    censusTransformRow(f.left.gray16, type, y, x0, x1, w.leftCensus.data());
    censusTransformRow(f.right.gray16, type, y, xr0, xr1, w.rightCensus.data());
  }
  censusPlanes(w.rightCensus.data(), W, f.planePad, xr0, xr1, w.rightPlanes.data(), f.planeStride);
}

void CpuMatcher::costRange(const Frame& f, int y, int x0, int x1, std::uint8_t* cost, RowWindows windows,
                           Worker& w) {
  const FramePlan& plan = f.plan;
  const Parameters& p = plan.params;
  Lap lap;
  std::uint8_t* lidar = plan.mode == MatchMode::LidarOnly ? cost : w.lidar.data();
  if (plan.useLidar) {
    lidarCostRange(f, y, x0, x1, lidar);
    lap(w.lidarCostMs);
  }
  if (!plan.useCameras()) return;
  if (plan.upCamera()) {
    tripleCostRange(f, y, x0, x1, lidar, cost, w, lap);
    return;
  }
  censusRows(f, y, x0, x1, w);
  const std::uint64_t* leftRow = w.leftCensus.data();
  const std::uint8_t* planes = w.rightPlanes.data();
  if (plan.mode == MatchMode::Fused) {
    const std::uint16_t* weights = plan.adaptiveAlpha ? lidarWeights_.view().row(y) : nullptr;
    // With the gated search, only the windows' costs: nothing reads the others.
    censusCostFusedRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, plan.width, x0, x1,
                       plan.minDisparity, plan.D, lidar, touched_.view().row(y), weights, plan.alphaWeight,
                       p.stereoCostWithoutLidar, cost, windows);
  } else {
    censusCostRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, plan.width, x0, x1, plan.minDisparity,
                  plan.D, cost, windows);
  }
  lap(w.censusCostMs);
}

// Most pixels have no point around them: C_L = 0 there, without looking for points. The fused
// row kernel reads `touched` itself and needs no zeros.
void CpuMatcher::lidarCostRange(const Frame& f, int y, int x0, int x1, std::uint8_t* lidar) {
  const FramePlan& plan = f.plan;
  const bool zeroUntouched = plan.mode == MatchMode::LidarOnly || plan.upCamera();
  std::uint8_t* support = f.out.support.view().row(y);
  const std::uint8_t* touched = touched_.view().row(y);
  lidarCostRow(*f.lidar, lidarRows_, y, x0, x1, plan.minDisparity, plan.D, touched, lidar);
  for (int x = x0; x < x1; ++x) {
    if (touched[x] == 0 && zeroUntouched) std::memset(lidar + static_cast<std::size_t>(x - x0) * plan.D, 0, plan.D);
    support[x] = touched[x];
  }
}

// Triple-SGM: the camera cost C_S3 = (C_S + C_V + 1) >> 1 takes C_S's place in Eq. 5.
void CpuMatcher::tripleCostRange(const Frame& f, int y, int x0, int x1, const std::uint8_t* lidar,
                                 std::uint8_t* cost, Worker& w, Lap& lap) {
  const FramePlan& plan = f.plan;
  const Parameters& p = plan.params;
  const std::size_t D = static_cast<std::size_t>(plan.D);
  const std::size_t n = static_cast<std::size_t>(x1 - x0) * D;
  censusRows(f, y, x0, x1, w);
  const std::uint64_t* leftRow = w.leftCensus.data();
  const std::uint8_t* planes = w.rightPlanes.data();
  std::uint8_t* camera = plan.mode == MatchMode::Fused ? w.stereo.data() : cost;
  censusCostRow(leftRow, planes, f.planeStride, f.planePad, p.censusType, plan.width, x0, x1, plan.minDisparity,
                plan.D, camera);
  lap(w.censusCostMs);
  verticalCensusCostRow(leftRow, upCensus_.view(), y, x0, x1, plan.ratio16, plan.minDisparity, plan.D,
                        plan.censusScale, w.vertical.data());
  combineCameraCostRow(camera, w.vertical.data(), n, camera);
  lap(w.verticalCostMs);
  if (plan.mode != MatchMode::Fused) return;
  if (!plan.adaptiveAlpha) {
    fuseCostRow(lidar, camera, n, plan.alphaWeight, cost);
  } else {
    const std::uint16_t* weights = lidarWeights_.view().row(y);
    for (int x = x0; x < x1; ++x) {
      const auto offset = static_cast<std::size_t>(x - x0) * D;
      fuseCostRow(lidar + offset, camera + offset, D, weights[x], cost + offset);
    }
  }
  if (p.stereoCostWithoutLidar) {
    // Where no point touches the pixel the LiDAR knows nothing: C = C_S3.
    const std::uint8_t* touched = touched_.view().row(y);
    for (int x = x0; x < x1; ++x) {
      if (touched[x] != 0) continue;
      const auto offset = static_cast<std::size_t>(x - x0) * D;
      std::memcpy(cost + offset, camera + offset, D);
    }
  }
  lap(w.fuseMs);
}

}  // namespace cpu
}  // namespace lidar_sgm
