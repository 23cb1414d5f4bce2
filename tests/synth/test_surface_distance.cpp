// Scene::distanceToSurface on each shape: points on, inside and outside, against closed forms and,
// for the ellipsoid, against points moved along the surface normal.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace {

using Eigen::Vector3d;

// One primitive far above the road (z = 0), so that the road is never the nearest surface.
synth::Scene sceneWith(const synth::Primitive& p) {
  synth::RoadLayout road;
  road.endX = 1000.0;
  return synth::Scene({p}, {synth::Material{}}, road, 0, {0, 0, 1}, 0);
}

TEST(SurfaceDistance, RoadPlaneAndItsEnd) {
  synth::RoadLayout road;
  road.endX = 50.0;
  const synth::Scene empty({}, {synth::Material{}}, road, 0, {0, 0, 1}, 0);
  EXPECT_DOUBLE_EQ(empty.distanceToSurface({3.0, -2.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(empty.distanceToSurface({3.0, -2.0, 1.65}), 1.65);
  EXPECT_DOUBLE_EQ(empty.distanceToSurface({10.0, 4.0, -0.5}), 0.5);
  EXPECT_NEAR(empty.distanceToSurface({53.0, 0.0, 4.0}), 5.0, 1e-12);  // past the end: to its edge
}

TEST(SurfaceDistance, BoxWithYaw) {
  synth::Primitive box;
  box.shape = synth::Shape::Box;
  box.center = {10.0, 2.0, 20.0};
  box.half = {2.0, 1.0, 0.5};
  box.yaw = 0.3;
  const synth::Scene scene = sceneWith(box);
  // A point given in the box's own axes, into the world.
  const auto world = [&](double x, double y, double z) {
    const double c = std::cos(box.yaw);
    const double s = std::sin(box.yaw);
    return Vector3d{box.center.x() + c * x - s * y, box.center.y() + s * x + c * y, box.center.z() + z};
  };
  EXPECT_NEAR(scene.distanceToSurface(world(2.0, 0.3, 0.1)), 0.0, 1e-12);     // on the +x face
  EXPECT_NEAR(scene.distanceToSurface(world(-0.7, -1.0, 0.2)), 0.0, 1e-12);   // on the -y face
  EXPECT_NEAR(scene.distanceToSurface(world(1.6, 0.1, 0.0)), 0.4, 1e-12);     // inside, nearest +x
  EXPECT_NEAR(scene.distanceToSurface(world(0.0, 0.0, 0.3)), 0.2, 1e-12);     // inside, nearest top
  EXPECT_NEAR(scene.distanceToSurface(world(3.0, 0.5, 0.0)), 1.0, 1e-12);     // outside a face
  EXPECT_NEAR(scene.distanceToSurface(world(3.0, 2.0, 0.0)), std::sqrt(2.0), 1e-12);  // an edge
  EXPECT_NEAR(scene.distanceToSurface(world(3.0, 2.0, 1.5)), std::sqrt(3.0), 1e-12);  // a corner
}

TEST(SurfaceDistance, VerticalCylinderSideAndCaps) {
  synth::Primitive cylinder;
  cylinder.shape = synth::Shape::Cylinder;
  cylinder.center = {0.0, 5.0, 20.0};
  cylinder.half = {0.5, 0.5, 2.0};
  const synth::Scene scene = sceneWith(cylinder);
  const double diagonal = 0.5 * std::sqrt(0.5);
  EXPECT_NEAR(scene.distanceToSurface({diagonal, 5.0 + diagonal, 21.0}), 0.0, 1e-12);  // on the side
  EXPECT_NEAR(scene.distanceToSurface({0.2, 5.1, 22.0}), 0.0, 1e-12);                  // on the top cap
  EXPECT_NEAR(scene.distanceToSurface({0.1, 5.0, 20.0}), 0.4, 1e-12);                  // inside, side nearer
  EXPECT_NEAR(scene.distanceToSurface({0.0, 5.0, 18.1}), 0.1, 1e-12);                  // inside, bottom nearer
  EXPECT_NEAR(scene.distanceToSurface({0.0, 7.0, 20.5}), 1.5, 1e-12);                  // outside the side
  EXPECT_NEAR(scene.distanceToSurface({0.0, 5.2, 23.0}), 1.0, 1e-12);                  // above the cap
  EXPECT_NEAR(scene.distanceToSurface({1.5, 5.0, 23.0}), std::sqrt(2.0), 1e-12);       // off the rim
}

TEST(SurfaceDistance, EllipsoidAxesAndCentre) {
  synth::Primitive ellipsoid;
  ellipsoid.shape = synth::Shape::Ellipsoid;
  ellipsoid.center = {0.0, 0.0, 20.0};
  ellipsoid.half = {2.0, 1.5, 1.0};
  const synth::Scene scene = sceneWith(ellipsoid);
  EXPECT_NEAR(scene.distanceToSurface({2.0, 0.0, 20.0}), 0.0, 1e-6);
  EXPECT_NEAR(scene.distanceToSurface({0.0, -1.5, 20.0}), 0.0, 1e-6);
  EXPECT_NEAR(scene.distanceToSurface({0.0, 0.0, 21.0}), 0.0, 1e-6);
  EXPECT_NEAR(scene.distanceToSurface({3.0, 0.0, 20.0}), 1.0, 1e-6);   // outside on the long axis
  EXPECT_NEAR(scene.distanceToSurface({0.0, 0.0, 17.5}), 1.5, 1e-6);   // outside on the short axis
  EXPECT_NEAR(scene.distanceToSurface({0.0, 0.0, 20.0}), 1.0, 1e-6);   // the centre: the short radius
  EXPECT_NEAR(scene.distanceToSurface({0.0, 0.0, 20.6}), 0.4, 1e-6);   // inside on the short axis
}

// Moved by d along the outward normal from a surface point, a point is exactly d from a convex
// surface (outside, any d; inside, while d is below the smallest radius of curvature, here 0.5 m).
TEST(SurfaceDistance, EllipsoidAlongTheNormal) {
  synth::Primitive ellipsoid;
  ellipsoid.shape = synth::Shape::Ellipsoid;
  ellipsoid.center = {4.0, -3.0, 20.0};
  ellipsoid.half = {2.0, 1.5, 1.0};
  const synth::Scene scene = sceneWith(ellipsoid);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_real_distribution<double> offset(-0.4, 3.0);
  const Vector3d& e = ellipsoid.half;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double a = angle(rng);
    const double b = 0.5 * angle(rng);
    const Vector3d onSurface{e.x() * std::cos(a) * std::sin(b), e.y() * std::sin(a) * std::sin(b),
                             e.z() * std::cos(b)};
    const Vector3d normal = Vector3d{onSurface.x() / (e.x() * e.x()), onSurface.y() / (e.y() * e.y()),
                                     onSurface.z() / (e.z() * e.z())}.normalized();
    const double d = offset(rng);
    const Vector3d point = ellipsoid.center + onSurface + d * normal;
    worst = std::max(worst, std::abs(scene.distanceToSurface(point) - std::abs(d)));
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(SurfaceDistance, NearestOfManyPrimitivesAndTheRoad) {
  synth::Primitive near;
  near.shape = synth::Shape::Box;
  near.center = {5.0, 0.0, 1.0};
  near.half = {0.5, 0.5, 0.5};
  synth::Primitive far = near;
  far.center = {9.0, 0.0, 1.0};
  synth::RoadLayout road;
  road.endX = 100.0;
  std::vector<synth::Primitive> primitives;
  for (int i = 0; i < 40; ++i) {  // enough primitives for a BVH several levels deep
    synth::Primitive p = far;
    p.center.x() += 3.0 * i;
    primitives.push_back(p);
  }
  primitives.push_back(near);
  const synth::Scene scene(primitives, {synth::Material{}}, road, 0, {0, 0, 1}, 0);
  EXPECT_NEAR(scene.distanceToSurface({3.9, 0.0, 1.5}), 0.6, 1e-12);     // the near box's face, not the road
  EXPECT_NEAR(scene.distanceToSurface({3.0, 0.0, 0.4}), 0.4, 1e-12);     // the road, not the box
  EXPECT_NEAR(scene.distanceToSurface({6.5, 0.0, 1.2}), 1.0, 1e-12);     // the near box, not the far one
  EXPECT_NEAR(scene.distanceToSurface({126.75, 0.0, 1.0}), 0.25, 1e-12);  // the last box, past the road's end
}

}  // namespace
}  // namespace lidar_sgm
