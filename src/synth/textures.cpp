// Value noise, bricks, tiles, stripes, windows, lane markings: every pattern is a pure function of
// the surface point, so any pixel of any camera can be shaded on its own.
#include "textures.hpp"

#include <algorithm>
#include <cmath>

#include "random.hpp"

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

// Trilinear value noise on the integer lattice, in [0, 1).
double valueNoise(const Vector3d& p, std::uint32_t seed) {
  const double fx = std::floor(p.x());
  const double fy = std::floor(p.y());
  const double fz = std::floor(p.z());
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const auto iz = static_cast<std::int64_t>(fz);
  const double tx = smooth(p.x() - fx);
  const double ty = smooth(p.y() - fy);
  const double tz = smooth(p.z() - fz);
  double corners[2][2][2];
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) corners[k][j][i] = hashUnit(ix + i, iy + j, iz + k, seed);
    }
  }
  double z[2];
  for (int k = 0; k < 2; ++k) {
    const double y0 = corners[k][0][0] + tx * (corners[k][0][1] - corners[k][0][0]);
    const double y1 = corners[k][1][0] + tx * (corners[k][1][1] - corners[k][1][0]);
    z[k] = y0 + ty * (y1 - y0);
  }
  return z[0] + tz * (z[1] - z[0]);
}

// How much of a pattern of this period survives the pixel footprint: 1 (sharp) .. 0 (averaged).
double detail(double period, double footprint) { return std::clamp(period / (2.5 * footprint) - 1.0, 0.0, 1.0); }

// Fractal noise, frequency `base` [1/m], octaves finer than the footprint replaced by their mean.
double fbm(const Vector3d& p, double base, int octaves, double footprint, std::uint32_t seed) {
  double sum = 0;
  double amplitude = 0.5;
  double frequency = base;
  double total = 0;
  for (int o = 0; o < octaves; ++o) {
    const double keep = detail(1.0 / frequency, footprint);
    const double n = keep > 0 ? valueNoise(p * frequency, seed + static_cast<std::uint32_t>(o) * 7919u) : 0.5;
    sum += amplitude * (keep * n + (1.0 - keep) * 0.5);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}

// In-plane coordinates (u horizontal, v vertical for walls) from the dominant normal axis.
void planeCoordinates(const Hit& hit, double& u, double& v) {
  const Vector3d& n = hit.normal;
  if (std::abs(n.z()) >= std::abs(n.x()) && std::abs(n.z()) >= std::abs(n.y())) {
    u = hit.point.x();
    v = hit.point.y();
  } else if (std::abs(n.x()) >= std::abs(n.y())) {
    u = hit.point.y();
    v = hit.point.z();
  } else {
    u = hit.point.x();
    v = hit.point.z();
  }
}

double fraction(double value, double period) { return value / period - std::floor(value / period); }

Rgb road(const Scene& scene, const Material& m, const Hit& hit, double footprint) {
  const Vector3d& p = hit.point;
  const double grain = fbm(p, 3.0, 5, footprint, m.noiseSeed);
  Rgb color = m.base * (0.7 + 0.6 * grain);
  const RoadLayout& layout = scene.road();
  const double halfLine = 0.5 * layout.lineWidth;
  bool marking = false;
  for (double y : layout.solidLinesY) marking = marking || std::abs(p.y() - y) < halfLine;
  if (std::abs(p.y() - layout.dashedLineY) < halfLine && fraction(p.x(), layout.dashPeriod) * layout.dashPeriod < layout.dashLength) {
    marking = true;
  }
  if (marking) color = m.alt * (0.9 + 0.2 * grain);
  return color;
}

// Facade windows on a grid of `windowSpacing` columns and 3.2 m floors; false outside a window.
bool window(const Material& m, double u, double z, double footprint, Rgb& color) {
  if (m.windowSpacing <= 0 || z < 1.0) return false;
  const double cu = fraction(u, m.windowSpacing);
  const double cz = fraction(z, 3.2);
  if (cu < 0.22 || cu > 0.78 || cz < 0.28 || cz > 0.82) return false;
  const double frame = 0.07 / m.windowSpacing;
  const bool onFrame = cu < 0.22 + frame || cu > 0.78 - frame || cz < 0.28 + 0.07 / 3.2 || cz > 0.82 - 0.07 / 3.2;
  const auto column = static_cast<std::int64_t>(std::floor(u / m.windowSpacing));
  const auto floorIndex = static_cast<std::int64_t>(std::floor(z / 3.2));
  const double curtain = hashUnit(column, floorIndex, 0, m.noiseSeed);
  const Rgb glass = curtain < 0.3 ? Rgb{0.55, 0.5, 0.42} : Rgb{0.12, 0.15, 0.2};
  const double sharp = detail(0.07, footprint);
  color = onFrame ? mix(glass, {0.85, 0.85, 0.82}, sharp) : glass;
  return true;
}

Rgb facade(const Material& m, const Hit& hit, double footprint) {
  double u = 0;
  double v = 0;
  planeCoordinates(hit, u, v);
  const bool wall = std::abs(hit.normal.z()) < 0.5;
  Rgb color;
  if (wall && window(m, u, v, footprint, color)) return color;
  const Vector3d& p = hit.point;
  switch (m.texture) {
    case Texture::Brick: {
      const double rowHeight = 0.075;
      const auto row = static_cast<std::int64_t>(std::floor(v / rowHeight));
      const double shifted = u + (row % 2 != 0 ? 0.12 : 0.0);
      const auto brick = static_cast<std::int64_t>(std::floor(shifted / 0.24));
      const bool mortar = fraction(v, rowHeight) < 0.13 || fraction(shifted, 0.24) < 0.05;
      const Rgb brickColor = m.base * (0.75 + 0.45 * hashUnit(brick, row, 1, m.noiseSeed));
      const Rgb sharp = mortar ? m.alt : brickColor;
      const Rgb mean = mix(m.base, m.alt, 0.15);
      color = mix(mean, sharp, detail(rowHeight, footprint)) * (0.85 + 0.3 * fbm(p, 0.7, 3, footprint, m.noiseSeed));
      return color;
    }
    case Texture::Plaster:
      return m.base * (0.96 + 0.08 * fbm(p, 1.5, 3, footprint, m.noiseSeed));
    case Texture::GlassPanels: {
      const double cu = fraction(u, m.windowSpacing);
      const double cv = fraction(v, 1.6);
      const bool mullion = cu < 0.06 / m.windowSpacing || cv < 0.06 / 1.6;
      const Rgb sharp = mullion ? m.alt : m.base;
      return mix(mix(m.base, m.alt, 0.08), sharp, detail(0.06, footprint));
    }
    default:
      return m.base * (0.8 + 0.4 * fbm(p, 2.0, 4, footprint, m.noiseSeed));
  }
}

}  // namespace

Rgb albedo(const Scene& scene, const Hit& hit, double footprint) {
  const Material& m = scene.materials()[static_cast<std::size_t>(hit.material)];
  const Vector3d& p = hit.point;
  switch (m.texture) {
    case Texture::Road:
      return road(scene, m, hit, footprint);
    case Texture::Concrete:
      if (m.windowSpacing > 0) return facade(m, hit, footprint);
      return m.base * (0.8 + 0.4 * fbm(p, 6.0, 4, footprint, m.noiseSeed));
    case Texture::Paving: {
      double u = 0;
      double v = 0;
      planeCoordinates(hit, u, v);
      const auto i = static_cast<std::int64_t>(std::floor(u / 0.3));
      const auto j = static_cast<std::int64_t>(std::floor(v / 0.3));
      const bool joint = fraction(u, 0.3) < 0.04 || fraction(v, 0.3) < 0.04;
      const Rgb tile = m.base * (0.9 + 0.2 * hashUnit(i, j, 2, m.noiseSeed));
      const Rgb sharp = joint ? m.alt : tile;
      return mix(mix(m.base, m.alt, 0.08), sharp, detail(0.3, footprint)) *
             (0.9 + 0.2 * fbm(p, 4.0, 3, footprint, m.noiseSeed));
    }
    case Texture::Brick:
    case Texture::Plaster:
    case Texture::GlassPanels:
      return facade(m, hit, footprint);
    case Texture::CarPaint:
      return m.base * (0.97 + 0.06 * fbm(p, 2.0, 2, footprint, m.noiseSeed));
    case Texture::DarkGlass:
    case Texture::Tire:
      return m.base;
    case Texture::Foliage: {
      const double n = fbm(p, 4.0, 5, footprint, m.noiseSeed);
      return mix(m.alt, m.base * 1.3, std::clamp(1.6 * n - 0.3, 0.0, 1.0));
    }
    case Texture::Bark:
      return mix(m.alt, m.base, fbm({p.x() * 6.0, p.y() * 6.0, p.z() * 1.0}, 2.0, 3, footprint, m.noiseSeed));
    case Texture::Metal:
      return m.base * (0.92 + 0.16 * fbm(p, 3.0, 2, footprint, m.noiseSeed));
    case Texture::SignStripes: {
      const double stripe = fraction(p.y() + p.z(), 0.2);
      return mix(mix(m.base, m.alt, 0.5), stripe < 0.5 ? m.base : m.alt, detail(0.2, footprint));
    }
  }
  return m.base;
}

}  // namespace synth
}  // namespace lidar_sgm
