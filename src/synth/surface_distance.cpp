// Point-to-surface distances: the tests' check that a point meant to lie on the scene does. Kept
// apart from the ray queries on purpose: an error in either shows up as a disagreement.
#include <algorithm>
#include <cmath>
#include <utility>

#include "lidar_sgm/synth/scene.hpp"

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

// Distance to the boundary of an axis-aligned box with half extents `half`, point relative to its
// centre: outside, the length of the excess over the faces; inside, the distance to the nearest face.
double boxBoundaryDistance(const Vector3d& local, const Vector3d& half) {
  const Vector3d q{std::abs(local.x()) - half.x(), std::abs(local.y()) - half.y(), std::abs(local.z()) - half.z()};
  const double inside = std::max(q.x(), std::max(q.y(), q.z()));
  if (inside <= 0.0) return -inside;
  const Vector3d outside{std::max(q.x(), 0.0), std::max(q.y(), 0.0), std::max(q.z(), 0.0)};
  return norm(outside);
}

double boxDistance(const Primitive& p, const Vector3d& world) {
  // Undo the yaw as intersectBox does: the box's own axes.
  const double c = std::cos(p.yaw);
  const double s = std::sin(p.yaw);
  const Vector3d rel = world - p.center;
  return boxBoundaryDistance({c * rel.x() + s * rel.y(), -s * rel.x() + c * rel.y(), rel.z()}, p.half);
}

// A vertical capped cylinder is a box in (radial, height): the same formula in two dimensions.
double cylinderDistance(const Primitive& p, const Vector3d& world) {
  const double radial = std::hypot(world.x() - p.center.x(), world.y() - p.center.y()) - p.half.x();
  const double height = std::abs(world.z() - p.center.z()) - p.half.z();
  const double inside = std::max(radial, height);
  if (inside <= 0.0) return -inside;
  return std::hypot(std::max(radial, 0.0), std::max(height, 0.0));
}

// The nearest point of the ellipsoid sum (x_i / e_i)^2 = 1 to y is x_i = e_i^2 y_i / (t + e_i^2)
// for the root t > -e_min^2 of F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1 (Eberly, "Distance from a
// point to an ellipse, an ellipsoid, or a hyperellipsoid"). F falls monotonically from +inf to -1
// on that interval when y's component along the shortest axis is not 0, so bisection finds the
// root to rounding. On the plane of the shortest axis the point is moved 1e-9 m off it: the
// distance is continuous, so the answer changes by about that much. Exact to about a micrometre.
double ellipsoidDistance(const Primitive& p, const Vector3d& world) {
  const double e[3] = {p.half.x(), p.half.y(), p.half.z()};
  const Vector3d rel = world - p.center;
  double y[3] = {std::abs(rel.x()), std::abs(rel.y()), std::abs(rel.z())};  // symmetric: first octant
  int shortest = 0;
  for (int i = 1; i < 3; ++i) shortest = e[i] < e[shortest] ? i : shortest;
  y[shortest] = std::max(y[shortest], 1e-9);
  const double e2min = e[shortest] * e[shortest];
  auto f = [&](double t) {
    double sum = -1.0;
    for (int i = 0; i < 3; ++i) {
      const double r = e[i] * y[i] / (t + e[i] * e[i]);
      sum += r * r;
    }
    return sum;
  };
  // Each term is at most (e_i y_i)^2 / (t + e_min^2)^2, so F < 0 once t + e_min^2 exceeds |e y|.
  const double scaled = std::sqrt(e[0] * e[0] * y[0] * y[0] + e[1] * e[1] * y[1] * y[1] + e[2] * e[2] * y[2] * y[2]);
  double lo = -e2min;
  double hi = -e2min + 2.0 * scaled + 1e-12;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // the interval cannot shrink any more
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  double squared = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double nearest = e[i] * e[i] * y[i] / (t + e[i] * e[i]);
    squared += (nearest - y[i]) * (nearest - y[i]);
  }
  return std::sqrt(squared);
}

double primitiveDistance(const Primitive& p, const Vector3d& world) {
  switch (p.shape) {
    case Shape::Box: return boxDistance(p, world);
    case Shape::Cylinder: return cylinderDistance(p, world);
    case Shape::Ellipsoid: return ellipsoidDistance(p, world);
  }
  return 1e300;
}

// Distance from a point to an axis-aligned box, 0 inside: no surface within the box is nearer.
double boundsDistance(const Vector3d& lo, const Vector3d& hi, const Vector3d& point) {
  const double dx = std::max({lo.x() - point.x(), 0.0, point.x() - hi.x()});
  const double dy = std::max({lo.y() - point.y(), 0.0, point.y() - hi.y()});
  const double dz = std::max({lo.z() - point.z(), 0.0, point.z() - hi.z()});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

double Scene::distanceToSurface(const Vector3d& world) const {
  // The road: the half-plane z = 0, x <= endX (as Scene::intersect has it).
  const double beyondEnd = std::max(world.x() - road_.endX, 0.0);
  double best = std::hypot(beyondEnd, world.z());
  if (nodes_.empty()) return best;
  // The BVH prunes every node whose bounds are farther than the best distance so far.
  int stack[96];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (boundsDistance(node.bounds.lo, node.bounds.hi, world) >= best) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        best = std::min(best, primitiveDistance(primitives_[static_cast<std::size_t>(order_[i])], world));
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  return best;
}

}  // namespace synth
}  // namespace lidar_sgm
