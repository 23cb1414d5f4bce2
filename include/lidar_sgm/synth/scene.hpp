#pragma once
/// @file scene.hpp  A street scene made of analytic primitives, and the ray queries on it.
///
/// World frame: x forward along the street, y left, z up, metres; the road is the plane z = 0 and
/// the left camera stands at (0, 0, cameraHeight). Everything not hit is sky, infinitely far.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lidar_sgm/synth/color.hpp"
#include "lidar_sgm/synth/vector_ops.hpp"

namespace lidar_sgm {
namespace synth {

/// Procedural surface patterns (see textures.cpp). Some are flat or periodic on purpose: that is
/// where stereo matching fails and LiDAR must help.
enum class Texture : std::uint8_t {
  Road,         ///< asphalt noise plus the scene's lane markings
  Concrete,     ///< curbs: fine noise
  Paving,       ///< sidewalk: a periodic tile grid
  Brick,        ///< facade: bricks and mortar, windows
  Plaster,      ///< facade: almost uniform (low texture), windows
  GlassPanels,  ///< facade: a periodic curtain wall
  CarPaint,     ///< uniform paint (low texture)
  DarkGlass,    ///< car windows: dark and specular (LiDAR drops out)
  Tire,         ///< black rubber (LiDAR drops out)
  Foliage,      ///< tree crowns: strong noise
  Bark,
  Metal,        ///< poles
  SignStripes,  ///< traffic sign plates
};

struct Material {
  Texture texture = Texture::Concrete;
  Rgb base{0.5, 0.5, 0.5};
  Rgb alt{0.3, 0.3, 0.3};       ///< second color of the pattern (mortar, frames, stripes)
  double reflectivity = 0.3;    ///< LiDAR (905 nm) reflectivity: intensity and dropouts
  double specular = 0;          ///< 0..1: mirror-like share (LiDAR drops out)
  std::uint32_t noiseSeed = 0;  ///< decorrelates the noise of objects sharing a texture
  double windowSpacing = 3.0;   ///< facades: window columns [m] (0 = no windows)
};

enum class Shape : std::uint8_t {
  Box,        ///< centre, half extents, yaw about z
  Cylinder,   ///< vertical: centre of the axis (x, y), radius, z from bottom to top
  Ellipsoid,  ///< axis-aligned: centre, radii
};

struct Primitive {
  Shape shape = Shape::Box;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  /// Box: half extents; Cylinder: (radius, radius, half height); Ellipsoid: radii.
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  double yaw = 0;  ///< Box only [rad]
  int material = 0;
  bool isObject = false;  ///< cars, poles, signs, trees: the foreground mask
};

/// Where the lane markings are (the road is the plane z = 0).
struct RoadLayout {
  double dashedLineY = 1.75;              ///< centre line, dashed
  std::vector<double> solidLinesY;        ///< edge lines
  double lineWidth = 0.12;
  double dashLength = 3.0;
  double dashPeriod = 9.0;
  double endX = 150.0;                    ///< the street ends with a facade here
};

struct Hit {
  double t = 0;           ///< ray parameter: point = origin + t * direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, facing the ray
  int primitive = -1;     ///< -1: the road plane
  int material = 0;
  bool isObject = false;
};

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /// Need not be unit length (cameras use forward component 1, so t = depth).
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

class Scene {
 public:
  Scene() = default;
  Scene(std::vector<Primitive> primitives, std::vector<Material> materials, RoadLayout road, int roadMaterial,
        Eigen::Vector3d sunDirection, std::uint32_t seed);

  /// Nearest hit with t in (tMin, tMax); false for sky.
  bool intersect(const Ray& ray, double tMin, double tMax, Hit& hit) const;

  /// Unsigned distance [m] from a world point to the nearest surface: a primitive's boundary
  /// (exact for boxes and cylinders; ellipsoids to about a micrometre, see surface_distance.cpp)
  /// or the road plane z = 0 (which ends at road().endX). The tests' independent check of the
  /// ground truth and of the poses: a point that should lie on the scene is within rounding of 0.
  double distanceToSurface(const Eigen::Vector3d& world) const;

  const std::vector<Primitive>& primitives() const { return primitives_; }
  const std::vector<Material>& materials() const { return materials_; }
  const RoadLayout& road() const { return road_; }
  const Eigen::Vector3d& sunDirection() const { return sun_; }
  std::uint32_t seed() const { return seed_; }

 private:
  struct Bounds {
    Eigen::Vector3d lo{1e30, 1e30, 1e30};
    Eigen::Vector3d hi{-1e30, -1e30, -1e30};
  };
  struct Node {
    Bounds bounds;
    int first = 0;   ///< leaf: first index into order_
    int count = 0;   ///< leaf: number of primitives; 0 for an inner node
    int left = -1;   ///< inner: children
    int right = -1;
  };
  int build(int first, int count, int depth);
  bool intersectPrimitive(int index, const Ray& ray, double tMin, double tMax, Hit& hit) const;

  std::vector<Primitive> primitives_;
  std::vector<Bounds> primitiveBounds_;
  std::vector<Material> materials_;
  RoadLayout road_;
  int roadMaterial_ = 0;
  Eigen::Vector3d sun_{0, 0, 1};
  std::uint32_t seed_ = 0;
  std::vector<Node> nodes_;   ///< bounding-volume hierarchy over primitives_ (the road is tested apart)
  std::vector<int> order_;
};

/// A procedural street for `seed` (std::mt19937 only, so the same seed gives the same street on
/// every standard library): road with lanes and markings, curbs, sidewalks, facades on both
/// sides with windows, parked and driving cars, lamp poles, traffic signs, trees, and a facade
/// across the far end.
Scene makeStreetScene(std::uint32_t seed);

/// The same street, made `driveLength` metres longer so that a rig driving along +x from x = 0 to
/// x = driveLength still has its sensors' full range ahead (the far facade stays 110..180 m past
/// the last frame). The world is static, so nothing stands in the ego lane (y = 0) to drive
/// into: oncoming cars stand in the other lane along the whole drive. driveLength = 0 is exactly
/// makeStreetScene(seed); throws std::invalid_argument when driveLength is negative or not finite.
Scene makeStreetScene(std::uint32_t seed, double driveLength);

}  // namespace synth
}  // namespace lidar_sgm
