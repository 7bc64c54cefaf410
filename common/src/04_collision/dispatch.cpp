// Framework half of Lab 4: the narrow-phase dispatcher, the distance query for any pair (closed
// forms where a sphere or a plane makes one, GJK otherwise), and the few pairs that need no new
// idea (a capsule or a polyhedron on a plane; spheres and capsules against polyhedra are in
// rounded.cpp).
#include <algorithm>
#include <string>
#include <utility>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"
#include "rounded.hpp"

namespace physlab {
namespace {

// A capsule on a plane: each end of its core is a sphere (ids 0 and 1).
Manifold collideCapsulePlane(const Capsule& a, const Pose& pose_a, const Plane& b) {
  Manifold m;
  const std::array<Vec3, 2> ends = a.segment(pose_a);
  for (std::uint32_t k = 0; k < 2; ++k) {
    const double height = b.normal.dot(ends[k]) - b.offset;
    const double depth = a.radius - height;
    if (depth >= 0.0) m.add(ends[k] - 0.5 * (a.radius + height) * b.normal, depth, k);
  }
  if (!m.empty()) m.normal = b.normal;
  return m;
}

// A polyhedron on a plane: every vertex below it (id = vertex index), reduced to 4.
Manifold collideConvexPlane(const ConvexPolyhedron& a, const Pose& pose_a, const Plane& b) {
  ContactPolygon below;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    const Vec3 p = pose_a.toWorld(a.vertices[i]);
    const double height = b.normal.dot(p) - b.offset;
    if (height <= 0.0) below.add(p - 0.5 * height * b.normal, -height, static_cast<std::uint32_t>(i));
  }
  if (below.count == 0) return Manifold{};
  return reduceContacts(b.normal, below);
}

// The routine for the pair (A, B) in this order; `found` is false when there is none.
Manifold collideOrdered(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, bool& found) {
  found = true;
  if (const auto* sa = std::get_if<Sphere>(&a)) {
    if (const auto* sb = std::get_if<Sphere>(&b)) return collideSphereSphere(*sa, pa, *sb, pb);
    if (const auto* plane = std::get_if<Plane>(&b)) return collideSpherePlane(*sa, pa, *plane);
    if (const auto* box = std::get_if<Box>(&b)) return collideSphereBox(*sa, pa, *box, pb);
    if (const auto* cb = std::get_if<ConvexPolyhedron>(&b)) return collideRoundedPolytope(pa.x, pa.x, sa->radius, *cb, pb);
  }
  if (const auto* ca = std::get_if<Capsule>(&a)) {
    if (const auto* sb = std::get_if<Sphere>(&b)) return collideCapsuleSphere(*ca, pa, *sb, pb);
    if (const auto* cb = std::get_if<Capsule>(&b)) return collideCapsuleCapsule(*ca, pa, *cb, pb);
    if (const auto* plane = std::get_if<Plane>(&b)) return collideCapsulePlane(*ca, pa, *plane);
    const std::array<Vec3, 2> ends = ca->segment(pa);
    if (const auto* bb = std::get_if<Box>(&b)) {
      return collideRoundedPolytope(ends[0], ends[1], ca->radius, ConvexPolyhedron::box(bb->half_extents), pb);
    }
    if (const auto* cb = std::get_if<ConvexPolyhedron>(&b)) return collideRoundedPolytope(ends[0], ends[1], ca->radius, *cb, pb);
  }
  if (const auto* ba = std::get_if<Box>(&a)) {
    if (const auto* plane = std::get_if<Plane>(&b)) return collideBoxPlane(*ba, pa, *plane);
    if (const auto* bb = std::get_if<Box>(&b)) return collideBoxBox(*ba, pa, *bb, pb);
    if (const auto* cb = std::get_if<ConvexPolyhedron>(&b)) {
      return collideConvexConvex(ConvexPolyhedron::box(ba->half_extents), pa, *cb, pb);
    }
  }
  if (const auto* ca = std::get_if<ConvexPolyhedron>(&a)) {
    if (const auto* plane = std::get_if<Plane>(&b)) return collideConvexPlane(*ca, pa, *plane);
    if (const auto* cb = std::get_if<ConvexPolyhedron>(&b)) return collideConvexConvex(*ca, pa, *cb, pb);
  }
  found = false;
  return Manifold{};
}

// Closest points of a ball (centre c, radius r) and the point q of another shape nearest to c,
// from which a ball of radius r_q grows; c on the core means overlap.
DistanceResult ballDistance(const Vec3& c, double r, const Vec3& q, double r_q) {
  DistanceResult d;
  const Vec3 gap = q - c;
  const double centres = gap.norm();
  d.distance = std::max(centres - r - r_q, 0.0);
  d.overlap = centres - r - r_q <= 0.0;
  const Vec3 u = centres > 0.0 ? Vec3(gap / centres) : Vec3::UnitZ();
  d.point_a = c + r * u;
  d.point_b = q - r_q * u;
  d.iterations = 1;
  return d;
}

// A sphere (A) against a sphere or a box (B) in closed form; `found` is false for other shapes.
DistanceResult sphereDistance(const Sphere& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                              bool& found) {
  found = true;
  if (const auto* sb = std::get_if<Sphere>(&b)) return ballDistance(pose_a.x, a.radius, pose_b.x, sb->radius);
  if (const auto* box = std::get_if<Box>(&b)) {
    // The box's point nearest to the centre: the centre clamped to the box in its frame
    const Vec3 local = pose_b.toBody(pose_a.x);
    const Vec3 nearest = local.cwiseMax(-box->half_extents).cwiseMin(box->half_extents);
    return ballDistance(pose_a.x, a.radius, pose_b.toWorld(nearest), 0.0);
  }
  found = false;
  return DistanceResult{};
}

}  // namespace

Manifold collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  validateShape(a, "shape A");
  validatePose(pose_a, "pose of shape A");
  validateShape(b, "shape B");
  validatePose(pose_b, "pose of shape B");
  bool found = false;
  Manifold m = collideOrdered(a, pose_a, b, pose_b, found);
  if (found) return m;
  m = collideOrdered(b, pose_b, a, pose_a, found);
  if (!found) {
    throw InvalidInput(std::string("collide: no narrow-phase routine for a ") + shapeName(a) + " against a " +
                       shapeName(b));
  }
  m.normal = -m.normal;  // the routine saw B as its A: its normal points from A to B
  return m;
}

DistanceResult distance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  validateShape(a, "shape A");
  validatePose(pose_a, "pose of shape A");
  validateShape(b, "shape B");
  validatePose(pose_b, "pose of shape B");
  const auto* plane_a = std::get_if<Plane>(&a);
  const auto* plane_b = std::get_if<Plane>(&b);
  if (plane_a && plane_b) throw InvalidInput("distance: two planes (unbounded) have no distance query");
  if (!plane_a && !plane_b) {
    bool found = false;
    if (const auto* sa = std::get_if<Sphere>(&a)) {
      const DistanceResult d = sphereDistance(*sa, pose_a, b, pose_b, found);
      if (found) return d;
    }
    if (const auto* sb = std::get_if<Sphere>(&b)) {
      DistanceResult d = sphereDistance(*sb, pose_b, a, pose_a, found);
      if (found) {
        std::swap(d.point_a, d.point_b);
        return d;
      }
    }
    return gjkDistance(a, pose_a, b, pose_b);
  }
  // Against a plane the deepest point of the other shape is its support point along -n.
  const Plane& plane = plane_a ? *plane_a : *plane_b;
  const Vec3 deepest = plane_a ? support(b, pose_b, -plane.normal) : support(a, pose_a, -plane.normal);
  const double height = plane.normal.dot(deepest) - plane.offset;
  DistanceResult r;
  r.overlap = height <= 0.0;
  r.distance = std::max(height, 0.0);
  const Vec3 on_plane = deepest - height * plane.normal;
  r.point_a = plane_a ? on_plane : deepest;
  r.point_b = plane_a ? deepest : on_plane;
  r.iterations = 1;
  return r;
}

}  // namespace physlab
