// Camera rendering: one ray per pixel centre, shaded; depth and object mask from the same hit.
#include "lidar_sgm/synth/render.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shading.hpp"
#include "weather.hpp"

namespace lidar_sgm {
namespace synth {
namespace {

std::uint8_t toByte(double value) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(255.0 * value), 0L, 255L));
}

}  // namespace

std::string toString(Weather weather) { return weather == Weather::Rain ? "rain" : "clear"; }

Weather weatherFromString(const std::string& name) {
  if (name == "clear") return Weather::Clear;
  if (name == "rain") return Weather::Rain;
  throw std::invalid_argument("weather '" + name + "' must be clear or rain");
}

RenderedView renderView(const Scene& scene, const PinholeCamera& camera, Weather weather, std::uint32_t noiseSeed) {
  RenderedView view;
  view.color.resize(camera.width, camera.height);
  view.depth.resize(camera.width, camera.height);
  view.objectMask.resize(camera.width, camera.height);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Ray ray = camera.pixelRay(u, v);
      Hit hit;
      Rgb color;
      if (scene.intersect(ray, 1e-3, 1e9, hit)) {
        // Size of the pixel on the surface: distance / focal, stretched by the grazing angle.
        const Eigen::Vector3d unit = normalized(ray.direction);
        const double cosine = std::max(0.15, std::abs(dot(unit, hit.normal)));
        const double footprint = hit.t * norm(ray.direction) / camera.focal / cosine;
        color = shade(scene, ray, hit, weather, footprint);
        view.depth(u, v) = static_cast<float>(hit.t);
        view.objectMask(u, v) = hit.isObject ? 1 : 0;
      } else {
        color = skyColor(ray.direction, weather);
        view.depth(u, v) = 0.0f;
        view.objectMask(u, v) = 0;
      }
      view.color(u, v) = {toByte(color.r), toByte(color.g), toByte(color.b)};
    }
  }
  if (weather == Weather::Rain) addRainToImage(view.color, noiseSeed);
  return view;
}

}  // namespace synth
}  // namespace lidar_sgm
