#include "lidar_sgm/eval/simulated_lidar.hpp"

#include <cmath>
#include <random>

namespace lidar_sgm {
namespace eval {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kKittiFocal = 721.5377;
constexpr double kKittiWidth = 1242.0;
constexpr double kKittiPrincipalRowRatio = 172.854 / 375.0;

// Box-Muller on std::mt19937, whose output the standard fixes: the same noise on every platform
// (std::normal_distribution is implementation-defined).
class GaussianNoise {
 public:
  explicit GaussianNoise(unsigned seed) : engine_(seed) {}
  double operator()() {
    const double u1 = (static_cast<double>(engine_()) + 1.0) / 4294967297.0;
    const double u2 = static_cast<double>(engine_()) / 4294967296.0;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937 engine_;
};

}  // namespace

std::vector<int> simulatedBeamRows(int width, int height, const SimulatedLidarOptions& o) {
  const double focal = o.focal > 0 ? o.focal : kKittiFocal * width / kKittiWidth;
  const double cy = o.principalRow >= 0 ? o.principalRow : kKittiPrincipalRowRatio * height;
  std::vector<int> rows;
  for (int beam = 0; beam < o.beams; ++beam) {
    const double t = o.beams > 1 ? static_cast<double>(beam) / (o.beams - 1) : 0.0;
    const double elevation = o.elevationTopDeg + t * (o.elevationBottomDeg - o.elevationTopDeg);
    const long v = std::lround(cy - focal * std::tan(elevation * kPi / 180.0));
    if (v < 0 || v >= height) continue;
    if (rows.empty() || rows.back() != v) rows.push_back(static_cast<int>(v));
  }
  return rows;
}

LidarPoints simulateLidarFromGroundTruth(ImageView<const float> gt, const SimulatedLidarOptions& o,
                                         Image<std::uint8_t>& inputMask) {
  inputMask.resize(gt.width, gt.height);
  inputMask.fill(0);
  GaussianNoise noise(o.seed);
  std::vector<LidarSample> samples;
  for (const int y : simulatedBeamRows(gt.width, gt.height, o)) {
    for (int x = 0; x < gt.width; x += o.columnStep) {
      const float d = gt(x, y);
      if (!(d > 0.0f)) continue;
      const double noisy = d + o.noiseSigma * noise();
      const long d16 = std::lround(noisy * kDisparityScale);
      if (d16 <= 0) continue;
      samples.push_back({x, y, static_cast<int>(d16)});
      inputMask(x, y) = 1;
    }
  }
  return LidarPoints(gt.width, gt.height, samples);
}

}  // namespace eval
}  // namespace lidar_sgm
