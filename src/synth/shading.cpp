// Lambertian surfaces under sun and sky, haze with distance; rain adds fog and a wet road that
// mirrors the street (view-dependent, so left and right cameras disagree there, as they do in rain).
#include "shading.hpp"

#include <algorithm>
#include <cmath>

#include "textures.hpp"

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

Vector3d reflect(const Vector3d& unitDirection, const Vector3d& normal) {
  return unitDirection - normal * (2.0 * dot(unitDirection, normal));
}

Rgb litSurface(const Scene& scene, const Hit& hit, const Rgb& surfaceAlbedo, Weather weather) {
  const double sun = weather == Weather::Rain ? 0.12 : 0.7;
  const double ambient = (weather == Weather::Rain ? 0.62 : 0.42) + 0.12 * hit.normal.z();
  const double lambert = std::max(0.0, dot(hit.normal, scene.sunDirection()));
  return surfaceAlbedo * (ambient + sun * lambert);
}

Rgb haze(const Rgb& color, double distance, const Vector3d& unitDirection, Weather weather) {
  const double range = weather == Weather::Rain ? 140.0 : 900.0;
  const double fog = 1.0 - std::exp(-distance / range);
  return mix(color, skyColor({unitDirection.x(), unitDirection.y(), 0.0}, weather), fog);
}

}  // namespace

Rgb skyColor(const Vector3d& direction, Weather weather) {
  const Vector3d d = normalized(direction);
  const double up = std::clamp(d.z(), 0.0, 1.0);
  if (weather == Weather::Rain) return mix({0.62, 0.63, 0.65}, {0.5, 0.52, 0.55}, up);
  return mix({0.78, 0.84, 0.9}, {0.38, 0.55, 0.85}, std::sqrt(up));
}

Rgb shade(const Scene& scene, const Ray& ray, const Hit& hit, Weather weather, double footprint) {
  const Material& m = scene.materials()[static_cast<std::size_t>(hit.material)];
  const Vector3d unit = normalized(ray.direction);
  const double distance = hit.t * norm(ray.direction);
  Rgb color = litSurface(scene, hit, albedo(scene, hit, footprint), weather);
  // Glass mirrors the sky a little: view-dependent, a stereo failure as on real facades and cars.
  if (m.specular > 0) color = mix(color, skyColor(reflect(unit, hit.normal), weather), 0.35 * m.specular);
  const bool ground = hit.normal.z() > 0.9 && !hit.isObject;
  if (weather == Weather::Rain && ground) {
    // Wet ground: darker, and a mirror of the street with Schlick's Fresnel weight.
    const double cosine = std::max(0.0, -dot(unit, hit.normal));
    const double fresnel = 0.05 + 0.95 * std::pow(1.0 - cosine, 5.0);
    const Ray mirrored{hit.point, reflect(unit, hit.normal)};
    Hit seen;
    Rgb reflection = skyColor(mirrored.direction, weather);
    if (scene.intersect(mirrored, 1e-4, 1e9, seen)) {
      reflection = litSurface(scene, seen, albedo(scene, seen, footprint), weather);
    }
    // Capped at 0.35: a wet road, not a flooded one; with 0.6 stereo-only lost 50 points of
    // "correct" against clear weather, three times the paper's CARLA HardRainNoon drop (15).
    color = mix(color * 0.6, reflection * 0.85, std::min(0.35, fresnel));
  }
  color = haze(color, distance, unit, weather);
  if (weather == Weather::Rain) color = mix(color, {0.5, 0.5, 0.5}, 0.15);  // lower contrast
  return color;
}

}  // namespace synth
}  // namespace lidar_sgm
