// The procedural street: which primitives stand where. Sizes are those of a European city street.
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "lidar_sgm/synth/scene.hpp"
#include "random.hpp"

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

constexpr double kPi = 3.14159265358979323846;

class StreetBuilder {
 public:
  StreetBuilder(std::uint32_t seed, double driveLength) : rng_(seed), seed_(seed), driveLength_(driveLength) {}

  Scene build() {
    layOutRoad();
    const int road = material(Texture::Road, {0.22, 0.22, 0.23}, {0.85, 0.85, 0.82}, 0.12);
    addSide(-1.0, roadRight_);
    addSide(+1.0, roadLeft_);
    addFarFacade();
    addTraffic();
    const double sunAzimuth = uniform(rng_, -kPi, kPi);
    const double sunElevation = uniform(rng_, 0.5, 1.1);
    const Vector3d sun{std::cos(sunElevation) * std::cos(sunAzimuth), std::cos(sunElevation) * std::sin(sunAzimuth),
                   std::sin(sunElevation)};
    return Scene(std::move(primitives_), std::move(materials_), road_, road, sun, seed_);
  }

 private:
  int material(Texture texture, Rgb base, Rgb alt, double reflectivity, double specular = 0.0,
               double windowSpacing = 0.0) {
    Material m;
    m.texture = texture;
    m.base = base;
    m.alt = alt;
    m.reflectivity = reflectivity;
    m.specular = specular;
    m.noiseSeed = static_cast<std::uint32_t>(rng_());
    m.windowSpacing = windowSpacing;
    materials_.push_back(m);
    return static_cast<int>(materials_.size()) - 1;
  }

  void box(Vector3d lo, Vector3d hi, int mat, bool isObject, double yaw = 0.0) {
    Primitive p;
    p.shape = Shape::Box;
    p.center = (lo + hi) * 0.5;
    p.half = (hi - lo) * 0.5;
    p.yaw = yaw;
    p.material = mat;
    p.isObject = isObject;
    primitives_.push_back(p);
  }

  void cylinder(double x, double y, double z0, double z1, double radius, int mat) {
    Primitive p;
    p.shape = Shape::Cylinder;
    p.center = {x, y, 0.5 * (z0 + z1)};
    p.half = {radius, radius, 0.5 * (z1 - z0)};
    p.material = mat;
    p.isObject = true;
    primitives_.push_back(p);
  }

  void ellipsoid(Vector3d center, Vector3d radii, int mat) {
    Primitive p;
    p.shape = Shape::Ellipsoid;
    p.center = center;
    p.half = radii;
    p.material = mat;
    p.isObject = true;
    primitives_.push_back(p);
  }

  Rgb randomColor(double lo, double hi) {
    return {uniform(rng_, lo, hi), uniform(rng_, lo, hi), uniform(rng_, lo, hi)};
  }

  // Ego car in the right lane (y = 0), oncoming lane to the left, optional parking lanes.
  void layOutRoad() {
    laneWidth_ = uniform(rng_, 3.2, 3.7);
    parkRight_ = chance(rng_, 0.8);
    parkLeft_ = chance(rng_, 0.7);
    roadRight_ = -0.5 * laneWidth_ - (parkRight_ ? 2.3 : 0.4);
    roadLeft_ = 1.5 * laneWidth_ + (parkLeft_ ? 2.3 : 0.4);
    road_.dashedLineY = 0.5 * laneWidth_;
    road_.solidLinesY = {-0.5 * laneWidth_ - 0.1, 1.5 * laneWidth_ + 0.1};
    road_.dashLength = uniform(rng_, 2.5, 4.0);
    road_.dashPeriod = road_.dashLength * uniform(rng_, 2.0, 3.0);
    road_.endX = uniform(rng_, 110.0, 180.0) + driveLength_;
  }

  // Curb, sidewalk, facades, poles, trees and parked cars on one side; side = -1 right, +1 left.
  void addSide(double side, double edgeY) {
    const double endX = road_.endX;
    const double curbHeight = uniform(rng_, 0.10, 0.16);
    const double sidewalk = uniform(rng_, 2.0, 4.0);
    const double facadeY = edgeY + side * sidewalk;
    const int curb = material(Texture::Concrete, {0.55, 0.55, 0.53}, {0.4, 0.4, 0.4}, 0.35);
    const int paving = material(Texture::Paving, randomColor(0.42, 0.55), {0.3, 0.3, 0.3}, 0.3);
    auto span = [&](double a, double b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
    const auto curbY = span(edgeY, edgeY + side * 0.25);
    box({-10.0, curbY.first, 0.0}, {endX, curbY.second, curbHeight}, curb, false);
    const auto walkY = span(edgeY + side * 0.25, facadeY);
    box({-10.0, walkY.first, 0.0}, {endX, walkY.second, curbHeight}, paving, false);

    // Buildings, with the odd gap of a side street.
    double x = -10.0;
    while (x < endX) {
      const double length = uniform(rng_, 8.0, 26.0);
      if (x > 15.0 && chance(rng_, 0.12)) {
        x += uniform(rng_, 8.0, 14.0);
        continue;
      }
      const double setback = chance(rng_, 0.3) ? uniform(rng_, 0.2, 1.2) : 0.0;
      const double height = uniform(rng_, 6.0, 24.0);
      const auto y = span(facadeY + side * setback, facadeY + side * (setback + 15.0));
      box({x, y.first, 0.0}, {std::min(x + length, endX), y.second, height}, facadeMaterial(), false);
      x += length;
    }

    // Lamp poles near the curb, a tree or a sign between some of them.
    const double poleY = edgeY + side * 0.45;
    const int metal = material(Texture::Metal, randomColor(0.35, 0.5), {0.2, 0.2, 0.2}, 0.45, 0.2);
    const int bark = material(Texture::Bark, {0.30, 0.22, 0.15}, {0.18, 0.13, 0.09}, 0.25);
    const int leaves = material(Texture::Foliage, {0.20, 0.38, 0.12}, {0.08, 0.2, 0.05}, 0.35);
    for (double px = uniform(rng_, 5.0, 15.0); px < endX - 5.0; px += uniform(rng_, 14.0, 30.0)) {
      const double height = uniform(rng_, 5.5, 8.0);
      cylinder(px, poleY, 0.0, height, uniform(rng_, 0.06, 0.10), metal);
      const double armY = poleY - side * 1.4;
      box({px - 0.04, std::min(poleY, armY), height - 0.12}, {px + 0.04, std::max(poleY, armY), height - 0.04},
          metal, true);
      box({px - 0.25, armY - 0.15, height - 0.3}, {px + 0.25, armY + 0.15, height - 0.08}, metal, true);
      const double mid = px + uniform(rng_, 5.0, 9.0);
      if (chance(rng_, 0.55)) addTree(mid, edgeY + side * uniform(rng_, 0.9, 1.6), bark, leaves);
      else if (chance(rng_, 0.35)) addSign(mid, poleY, metal);
    }

    // Parked cars along the parking lane.
    if ((side < 0 && parkRight_) || (side > 0 && parkLeft_)) {
      const double laneCenter = edgeY - side * 1.15;
      for (double cx = uniform(rng_, 4.0, 9.0); cx < endX - 8.0;) {
        if (chance(rng_, 0.25)) {
          cx += uniform(rng_, 5.0, 12.0);
          continue;
        }
        const double length = uniform(rng_, 3.9, 4.9);
        const double offset = uniform(rng_, -0.15, 0.15);
        addCar(cx + 0.5 * length, laneCenter + offset, length, uniform(rng_, -0.04, 0.04));
        cx += length + uniform(rng_, 0.6, 3.0);
      }
    }
  }

  int facadeMaterial() {
    const double pick = uniform01(rng_);
    const double windows = uniform(rng_, 2.4, 4.0);
    if (pick < 0.35) {
      return material(Texture::Brick, {uniform(rng_, 0.45, 0.65), uniform(rng_, 0.2, 0.32), uniform(rng_, 0.12, 0.2)},
                      {0.7, 0.68, 0.62}, 0.3, 0.0, windows);
    }
    if (pick < 0.7) {  // plaster: nearly uniform, the classic stereo failure
      return material(Texture::Plaster, randomColor(0.55, 0.85), {0.25, 0.27, 0.3}, 0.5, 0.0, windows);
    }
    if (pick < 0.85) {  // curtain wall: periodic, stereo-ambiguous, partly specular
      return material(Texture::GlassPanels, {0.25, 0.32, 0.38}, {0.6, 0.6, 0.62}, 0.15, 0.5,
                      uniform(rng_, 1.2, 1.8));
    }
    return material(Texture::Concrete, randomColor(0.45, 0.65), {0.3, 0.3, 0.3}, 0.4, 0.0, windows);
  }

  void addTree(double x, double y, int bark, int leaves) {
    const double trunk = uniform(rng_, 2.2, 3.4);
    cylinder(x, y, 0.0, trunk + 0.6, uniform(rng_, 0.12, 0.2), bark);
    const int blobs = uniformInt(rng_, 1, 3);
    for (int i = 0; i < blobs; ++i) {
      const double r = uniform(rng_, 1.1, 2.0);
      // Braces, not parentheses: a braced list is evaluated left to right, so the draws keep their order.
      const Vector3d center{x + uniform(rng_, -0.6, 0.6), y + uniform(rng_, -0.6, 0.6),
                            trunk + r * uniform(rng_, 0.6, 1.0)};
      ellipsoid(center, {r, r * uniform(rng_, 0.8, 1.1), r * uniform(rng_, 0.7, 1.0)}, leaves);
    }
  }

  void addSign(double x, double y, int metal) {
    const double top = uniform(rng_, 2.3, 2.8);
    cylinder(x, y, 0.0, top, 0.035, metal);
    const Rgb colors[3] = {{0.75, 0.08, 0.08}, {0.1, 0.2, 0.65}, {0.85, 0.7, 0.1}};
    const int plate = material(Texture::SignStripes, colors[uniformInt(rng_, 0, 2)], {0.92, 0.92, 0.92}, 0.9);
    const double size = uniform(rng_, 0.55, 0.8);
    box({x - 0.07, y - 0.5 * size, top - size}, {x - 0.04, y + 0.5 * size, top}, plate, true);
  }

  // Body, cabin and a dark wheel block: a car with windows (LiDAR dropouts) and occluding edges.
  void addCar(double x, double y, double length, double yaw) {
    const double width = uniform(rng_, 1.7, 1.9);
    const bool van = chance(rng_, 0.12);
    const double bodyTop = van ? uniform(rng_, 1.6, 1.9) : uniform(rng_, 0.9, 1.05);
    const double roof = van ? bodyTop + 0.3 : uniform(rng_, 1.35, 1.55);
    const Rgb color = randomColor(0.05, 0.85);
    const int paint = material(Texture::CarPaint, color, {0, 0, 0}, uniform(rng_, 0.1, 0.6), 0.15);
    const int glass = material(Texture::DarkGlass, {0.06, 0.07, 0.08}, {0.2, 0.2, 0.22}, 0.05, 0.8);
    const int tire = material(Texture::Tire, {0.05, 0.05, 0.05}, {0.1, 0.1, 0.1}, 0.04);
    const double c = std::cos(yaw);
    const double s = std::sin(yaw);
    auto part = [&](double along, double halfLength, double halfWidth, double z0, double z1, int mat) {
      const Vector3d center{x + c * along, y + s * along, 0.5 * (z0 + z1)};
      const Vector3d half{halfLength, halfWidth, 0.5 * (z1 - z0)};
      box(center - half, center + half, mat, true, yaw);
    };
    part(0.0, 0.5 * length - 0.3, 0.5 * width - 0.05, 0.0, 0.36, tire);
    part(0.0, 0.5 * length, 0.5 * width, 0.3, bodyTop, paint);
    if (van) {
      part(0.5 * length - 0.45, 0.4, 0.5 * width - 0.02, bodyTop - 0.7, bodyTop - 0.05, glass);
      part(0.0, 0.5 * length - 0.05, 0.5 * width - 0.02, bodyTop, roof, paint);
    } else {
      const double cabin = uniform(rng_, 0.45, 0.55) * length;
      part(-0.08 * length, 0.5 * cabin, 0.5 * width - 0.1, bodyTop, roof, glass);
      part(-0.08 * length, 0.5 * cabin - 0.25, 0.5 * width - 0.12, roof - 0.01, roof + 0.04, paint);
    }
  }

  void addFarFacade() {
    const double height = uniform(rng_, 12.0, 30.0);
    box({road_.endX, -80.0, 0.0}, {road_.endX + 10.0, 80.0, height}, facadeMaterial(), false);
  }

  // Cars driving ahead in the ego lane and oncoming: occluders in the middle of the image.
  void addTraffic() {
    if (driveLength_ > 0.0) {
      addOncomingAlongDrive();
      return;
    }
    if (chance(rng_, 0.6)) {
      const double length = uniform(rng_, 4.0, 4.8);
      const double x = uniform(rng_, 10.0, 35.0);
      const double y = uniform(rng_, -0.3, 0.3);
      addCar(x, y, length, uniform(rng_, -0.03, 0.03));
    }
    const int oncoming = uniformInt(rng_, 0, 2);
    for (int i = 0; i < oncoming; ++i) {
      // One draw per statement: the order of evaluation of function arguments is unspecified.
      const double x = uniform(rng_, 12.0, 70.0);
      const double y = laneWidth_ + uniform(rng_, -0.3, 0.3);
      const double length = uniform(rng_, 4.0, 4.8);
      addCar(x, y, length, kPi + uniform(rng_, -0.03, 0.03));
    }
  }

  // A drive: the ego lane stays free (the rig would drive through a car standing in it), and the
  // other lane gets standing cars all along, so that every frame has some in view.
  void addOncomingAlongDrive() {
    for (double x = uniform(rng_, 12.0, 40.0); x < road_.endX - 20.0; x += uniform(rng_, 15.0, 60.0)) {
      const double y = laneWidth_ + uniform(rng_, -0.3, 0.3);
      const double length = uniform(rng_, 4.0, 4.8);
      addCar(x, y, length, kPi + uniform(rng_, -0.03, 0.03));
    }
  }

  std::mt19937 rng_;
  std::uint32_t seed_;
  double driveLength_ = 0.0;
  std::vector<Primitive> primitives_;
  std::vector<Material> materials_;
  RoadLayout road_;
  double laneWidth_ = 3.5;
  bool parkRight_ = true;
  bool parkLeft_ = true;
  double roadRight_ = -4.0;
  double roadLeft_ = 7.5;
};

}  // namespace

Scene makeStreetScene(std::uint32_t seed) { return StreetBuilder(seed, 0.0).build(); }

Scene makeStreetScene(std::uint32_t seed, double driveLength) {
  if (!(driveLength >= 0.0 && driveLength < 1e6)) {
    throw std::invalid_argument("street drive length " + std::to_string(driveLength) + " must be in [0, 1e6) m");
  }
  return StreetBuilder(seed, driveLength).build();
}

}  // namespace synth
}  // namespace lidar_sgm
