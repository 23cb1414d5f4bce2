// The LiDAR sweep: one ray per beam and azimuth step, range noise and physically motivated dropouts.
#include "lidar_sgm/synth/lidar_scan.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "random.hpp"

namespace lidar_sgm {
namespace synth {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Dark targets return too few photons, mirrors send them elsewhere, grazing hits smear them.
double dropoutProbability(const Material& m, double cosine) {
  const double dark = std::clamp((0.12 - m.reflectivity) / 0.12, 0.0, 1.0) * 0.7;
  const double mirror = 0.6 * m.specular;
  const double grazing = cosine < 0.08 ? 0.8 : 0.0;
  return std::clamp(dark + mirror + grazing, 0.0, 0.95);
}

}  // namespace

LidarOptions LidarOptions::hdl64() { return {}; }

LidarOptions LidarOptions::beams128() {
  LidarOptions o;
  o.beams = 128;
  o.elevationTopDeg = 15.0;
  o.elevationBottomDeg = -25.0;
  o.azimuthStepDeg = 0.1;
  o.maxRange = 245.0;
  return o;
}

LidarOptions LidarOptions::forBeams(int beams) {
  if (beams == 64) return hdl64();
  if (beams == 128) return beams128();
  throw std::invalid_argument("beams " + std::to_string(beams) + " must be 64 or 128");
}

std::vector<LidarPoint> scanLidar(const Scene& scene, const Eigen::Vector3d& position, const LidarOptions& options,
                                  std::uint32_t seed) {
  std::mt19937 rng(seed);
  const int columns = static_cast<int>(std::lround(2.0 * options.azimuthHalfRangeDeg / options.azimuthStepDeg)) + 1;
  std::vector<double> elevations(static_cast<std::size_t>(options.beams));
  for (int b = 0; b < options.beams; ++b) {
    elevations[static_cast<std::size_t>(b)] =
        (options.elevationTopDeg +
         (options.elevationBottomDeg - options.elevationTopDeg) * b / std::max(1, options.beams - 1)) * kDegree;
  }
  std::vector<LidarPoint> points;
  points.reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(options.beams) / 2);
  for (int c = 0; c < columns; ++c) {
    const double azimuth = (options.azimuthHalfRangeDeg - c * options.azimuthStepDeg) * kDegree;
    for (double elevation : elevations) {
      const Eigen::Vector3d direction{std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                           std::sin(elevation)};
      Hit hit;
      if (!scene.intersect({position, direction}, options.minRange, options.maxRange, hit)) continue;
      const Material& m = scene.materials()[static_cast<std::size_t>(hit.material)];
      const double cosine = std::abs(dot(direction, hit.normal));
      // Both draws every time, so one point's fate never shifts the random stream of the others.
      const double drop = uniform01(rng);
      const double noise = options.rangeNoiseSigma * gaussian(rng);
      if (drop < dropoutProbability(m, cosine)) continue;
      const double range = hit.t + noise;
      LidarPoint p;
      p.x = static_cast<float>(direction.x() * range);
      p.y = static_cast<float>(direction.y() * range);
      p.z = static_cast<float>(direction.z() * range);
      p.intensity = static_cast<float>(std::clamp(m.reflectivity * (0.3 + 0.7 * cosine), 0.0, 1.0));
      points.push_back(p);
    }
  }
  return points;
}

}  // namespace synth
}  // namespace lidar_sgm
