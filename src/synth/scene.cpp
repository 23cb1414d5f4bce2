// Ray queries on the scene: the road plane, boxes, cylinders, ellipsoids, and a small BVH over them
// so that a frame (about a million rays) renders in about a second on one core.
#include "lidar_sgm/synth/scene.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace lidar_sgm {
namespace synth {

using Eigen::Vector3d;
namespace {

constexpr int kLeafSize = 2;

// Slab test: whether the ray enters [lo, hi] within (tMin, tMax); tEnter is where.
bool hitsBounds(const Vector3d& lo, const Vector3d& hi, const Ray& ray, const Vector3d& inverse, double tMin,
                double tMax, double& tEnter) {
  double t0 = tMin;
  double t1 = tMax;
  const double o[3] = {ray.origin.x(), ray.origin.y(), ray.origin.z()};
  const double inv[3] = {inverse.x(), inverse.y(), inverse.z()};
  const double l[3] = {lo.x(), lo.y(), lo.z()};
  const double h[3] = {hi.x(), hi.y(), hi.z()};
  for (int a = 0; a < 3; ++a) {
    double ta = (l[a] - o[a]) * inv[a];
    double tb = (h[a] - o[a]) * inv[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  tEnter = t0;
  return true;
}

Vector3d safeInverse(const Vector3d& d) {
  auto inv = [](double v) { return std::abs(v) < 1e-300 ? 1e300 : 1.0 / v; };
  return {inv(d.x()), inv(d.y()), inv(d.z())};
}

// Box in its own frame (yaw undone): slab test that also reports the face.
bool intersectBox(const Primitive& p, const Ray& ray, double tMin, double tMax, double& t, Vector3d& normal) {
  const double c = std::cos(p.yaw);
  const double s = std::sin(p.yaw);
  const Vector3d rel = ray.origin - p.center;
  const double o[3] = {c * rel.x() + s * rel.y(), -s * rel.x() + c * rel.y(), rel.z()};
  const double d[3] = {c * ray.direction.x() + s * ray.direction.y(), -s * ray.direction.x() + c * ray.direction.y(),
                       ray.direction.z()};
  const double h[3] = {p.half.x(), p.half.y(), p.half.z()};
  double t0 = -1e300;
  double t1 = 1e300;
  int axis0 = 0;
  int axis1 = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (o[a] < -h[a] || o[a] > h[a]) return false;
      continue;
    }
    double ta = (-h[a] - o[a]) / d[a];
    double tb = (h[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) {
      t0 = ta;
      axis0 = a;
    }
    if (tb < t1) {
      t1 = tb;
      axis1 = a;
    }
    if (t0 > t1) return false;
  }
  int axis = axis0;
  t = t0;
  if (t <= tMin) {  // the ray starts inside: the exit face
    t = t1;
    axis = axis1;
  }
  if (t <= tMin || t >= tMax) return false;
  double local[3] = {0, 0, 0};
  local[axis] = d[axis] > 0 ? -1.0 : 1.0;
  normal = {c * local[0] - s * local[1], s * local[0] + c * local[1], local[2]};
  return true;
}

bool intersectCylinder(const Primitive& p, const Ray& ray, double tMin, double tMax, double& t, Vector3d& normal) {
  const double r = p.half.x();
  const double zLo = p.center.z() - p.half.z();
  const double zHi = p.center.z() + p.half.z();
  bool found = false;
  const double ox = ray.origin.x() - p.center.x();
  const double oy = ray.origin.y() - p.center.y();
  const double a = ray.direction.x() * ray.direction.x() + ray.direction.y() * ray.direction.y();
  if (a > 1e-300) {
    const double b = ox * ray.direction.x() + oy * ray.direction.y();
    const double cc = ox * ox + oy * oy - r * r;
    const double disc = b * b - a * cc;
    if (disc >= 0) {
      const double root = std::sqrt(disc);
      for (double candidate : {(-b - root) / a, (-b + root) / a}) {
        if (candidate <= tMin || candidate >= tMax) continue;
        const double z = ray.origin.z() + candidate * ray.direction.z();
        if (z < zLo || z > zHi) continue;
        t = candidate;
        normal = {(ox + t * ray.direction.x()) / r, (oy + t * ray.direction.y()) / r, 0.0};
        tMax = t;
        found = true;
        break;
      }
    }
  }
  if (std::abs(ray.direction.z()) > 1e-300) {
    for (double zCap : {zLo, zHi}) {
      const double candidate = (zCap - ray.origin.z()) / ray.direction.z();
      if (candidate <= tMin || candidate >= tMax) continue;
      const double x = ox + candidate * ray.direction.x();
      const double y = oy + candidate * ray.direction.y();
      if (x * x + y * y > r * r) continue;
      t = candidate;
      normal = {0, 0, zCap == zHi ? 1.0 : -1.0};
      tMax = t;
      found = true;
    }
  }
  return found;
}

bool intersectEllipsoid(const Primitive& p, const Ray& ray, double tMin, double tMax, double& t, Vector3d& normal) {
  const Vector3d rel = ray.origin - p.center;
  const Vector3d o{rel.x() / p.half.x(), rel.y() / p.half.y(), rel.z() / p.half.z()};
  const Vector3d d{ray.direction.x() / p.half.x(), ray.direction.y() / p.half.y(), ray.direction.z() / p.half.z()};
  const double a = dot(d, d);
  const double b = dot(o, d);
  const double disc = b * b - a * (dot(o, o) - 1.0);
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  for (double candidate : {(-b - root) / a, (-b + root) / a}) {
    if (candidate <= tMin || candidate >= tMax) continue;
    t = candidate;
    const Vector3d q = rel + ray.direction * t;
    normal = normalized({q.x() / (p.half.x() * p.half.x()), q.y() / (p.half.y() * p.half.y()),
                         q.z() / (p.half.z() * p.half.z())});
    return true;
  }
  return false;
}

}  // namespace

Scene::Scene(std::vector<Primitive> primitives, std::vector<Material> materials, RoadLayout road, int roadMaterial,
             Vector3d sunDirection, std::uint32_t seed)
    : primitives_(std::move(primitives)),
      materials_(std::move(materials)),
      road_(std::move(road)),
      roadMaterial_(roadMaterial),
      sun_(normalized(sunDirection)),
      seed_(seed) {
  primitiveBounds_.resize(primitives_.size());
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    Vector3d extent = p.half;
    if (p.shape == Shape::Box && p.yaw != 0.0) {
      const double c = std::abs(std::cos(p.yaw));
      const double s = std::abs(std::sin(p.yaw));
      extent = {c * p.half.x() + s * p.half.y(), s * p.half.x() + c * p.half.y(), p.half.z()};
    }
    primitiveBounds_[i].lo = p.center - extent;
    primitiveBounds_[i].hi = p.center + extent;
    order_.push_back(static_cast<int>(i));
  }
  if (!primitives_.empty()) {
    nodes_.reserve(2 * primitives_.size());
    build(0, static_cast<int>(primitives_.size()), 0);
  }
}

int Scene::build(int first, int count, int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Bounds bounds;
  Bounds centers;
  for (int i = first; i < first + count; ++i) {
    const Bounds& b = primitiveBounds_[order_[i]];
    // std::min/max spelled out, not cwiseMin/Max: SIMD min/max pick the other operand of a tie
    // (-0 vs +0), which could move a bound and the BVH with it.
    bounds.lo = {std::min(bounds.lo.x(), b.lo.x()), std::min(bounds.lo.y(), b.lo.y()),
                 std::min(bounds.lo.z(), b.lo.z())};
    bounds.hi = {std::max(bounds.hi.x(), b.hi.x()), std::max(bounds.hi.y(), b.hi.y()),
                 std::max(bounds.hi.z(), b.hi.z())};
    const Vector3d c = (b.lo + b.hi) * 0.5;
    centers.lo = {std::min(centers.lo.x(), c.x()), std::min(centers.lo.y(), c.y()), std::min(centers.lo.z(), c.z())};
    centers.hi = {std::max(centers.hi.x(), c.x()), std::max(centers.hi.y(), c.y()), std::max(centers.hi.z(), c.z())};
  }
  nodes_[index].bounds = bounds;
  if (count <= kLeafSize || depth > 40) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const Vector3d span = centers.hi - centers.lo;
  const int axis = span.x() >= span.y() && span.x() >= span.z() ? 0 : (span.y() >= span.z() ? 1 : 2);
  auto key = [&](int i) {
    const Bounds& b = primitiveBounds_[i];
    return axis == 0 ? b.lo.x() + b.hi.x() : axis == 1 ? b.lo.y() + b.hi.y() : b.lo.z() + b.hi.z();
  };
  // A full sort with the index as tie-breaker: the same tree with any standard library.
  std::sort(order_.begin() + first, order_.begin() + first + count, [&](int a, int b) {
    const double ka = key(a);
    const double kb = key(b);
    return ka < kb || (ka == kb && a < b);
  });
  const int half = count / 2;
  const int left = build(first, half, depth + 1);
  const int right = build(first + half, count - half, depth + 1);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

bool Scene::intersectPrimitive(int index, const Ray& ray, double tMin, double tMax, Hit& hit) const {
  const Primitive& p = primitives_[index];
  double t = 0;
  Vector3d normal = Vector3d::Zero();
  bool found = false;
  switch (p.shape) {
    case Shape::Box: found = intersectBox(p, ray, tMin, tMax, t, normal); break;
    case Shape::Cylinder: found = intersectCylinder(p, ray, tMin, tMax, t, normal); break;
    case Shape::Ellipsoid: found = intersectEllipsoid(p, ray, tMin, tMax, t, normal); break;
  }
  if (!found) return false;
  hit.t = t;
  hit.point = ray.origin + ray.direction * t;
  hit.normal = dot(normal, ray.direction) > 0 ? Vector3d(normal * -1.0) : normal;
  hit.primitive = index;
  hit.material = p.material;
  hit.isObject = p.isObject;
  return true;
}

bool Scene::intersect(const Ray& ray, double tMin, double tMax, Hit& hit) const {
  bool found = false;
  double best = tMax;
  // The road plane z = 0, up to the facade that closes the street.
  if (ray.direction.z() < 0.0 && ray.origin.z() > 0.0) {
    const double t = -ray.origin.z() / ray.direction.z();
    if (t > tMin && t < best && ray.origin.x() + t * ray.direction.x() <= road_.endX) {
      best = t;
      found = true;
      hit.t = t;
      hit.point = ray.origin + ray.direction * t;
      hit.point.z() = 0.0;
      hit.normal = {0, 0, 1};
      hit.primitive = -1;
      hit.material = roadMaterial_;
      hit.isObject = false;
    }
  }
  if (nodes_.empty()) return found;
  const Vector3d inverse = safeInverse(ray.direction);
  int stack[96];
  int top = 0;
  double enter = 0;
  if (!hitsBounds(nodes_[0].bounds.lo, nodes_[0].bounds.hi, ray, inverse, tMin, best, enter)) return found;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (intersectPrimitive(order_[i], ray, tMin, best, hit)) {
          best = hit.t;
          found = true;
        }
      }
      continue;
    }
    // Visit the nearer child first so that `best` shrinks early and prunes the other.
    double tLeft = 0;
    double tRight = 0;
    const Node& l = nodes_[node.left];
    const Node& r = nodes_[node.right];
    const bool hitLeft = hitsBounds(l.bounds.lo, l.bounds.hi, ray, inverse, tMin, best, tLeft);
    const bool hitRight = hitsBounds(r.bounds.lo, r.bounds.hi, ray, inverse, tMin, best, tRight);
    if (hitLeft && hitRight) {
      if (tLeft <= tRight) {
        stack[top++] = node.right;
        stack[top++] = node.left;
      } else {
        stack[top++] = node.left;
        stack[top++] = node.right;
      }
    } else if (hitLeft) {
      stack[top++] = node.left;
    } else if (hitRight) {
      stack[top++] = node.right;
    }
  }
  return found;
}

}  // namespace synth
}  // namespace lidar_sgm
