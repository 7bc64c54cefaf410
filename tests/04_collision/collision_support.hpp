// Helpers for the Lab 4 graded tests: random shapes and poses, placements with a known gap
// along a direction, and signed distances computed here (oracles independent of student code).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "physlab/collision.hpp"
#include "support.hpp"

namespace physlab::test {

/// A random unit vector.
inline Vec3 randomUnit() {
  Vec3 u;
  do u = randomVec3(1.0);
  while (u.squaredNorm() < 1e-2 || u.squaredNorm() > 1.0);
  return u.normalized();
}

/// A random pose: position within `scale` of the origin, uniform-enough orientation.
inline Pose randomPose(double scale) {
  Pose p;
  p.x = randomVec3(scale);
  p.q = Quat(randomRotation());
  return p;
}

/// The kinds of shapes the property tests draw.
enum class Kind { Sphere, Box, Capsule, Plane, Tetrahedron };

/// A random shape of a kind, sizes 0.2-1 m (tetrahedra: a jittered regular one about the origin).
inline Shape randomShape(Kind kind) {
  switch (kind) {
    case Kind::Sphere:
      return Sphere(uniform(0.2, 1.0));
    case Kind::Box:
      return Box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
    case Kind::Capsule:
      return Capsule(uniform(0.1, 0.5), uniform(0.2, 1.0));
    case Kind::Plane:
      return Plane(randomUnit(), 0.0);
    default: {
      const double s = uniform(0.4, 1.0);
      const Vec3 a(s, 0, -s / std::sqrt(2.0)), b(-s, 0, -s / std::sqrt(2.0)), c(0, s, s / std::sqrt(2.0)),
          d(0, -s, s / std::sqrt(2.0));
      const Vec3 ja = randomVec3(0.15 * s), jb = randomVec3(0.15 * s), jc = randomVec3(0.15 * s);
      // Re-centre on the centroid so that the body origin stays inside.
      const Vec3 centre = (a + ja + b + jb + c + jc + d) / 4.0;
      return ConvexPolyhedron::tetrahedron(a + ja - centre, b + jb - centre, c + jc - centre, d - centre);
    }
  }
}

/// Extent of the posed shape along the unit u, measured from `from`: \f$u \cdot (s(u) - from)\f$.
inline double reach(const Shape& s, const Pose& pose, const Vec3& u, const Vec3& from) {
  return u.dot(support(s, pose, u) - from);
}

/// Moves A (or, when B is a plane, B's offset) so that the two shapes' projections on the unit
/// direction u are `gap` apart, A on the +u side (gap < 0: they overlap by -gap along u). A's
/// extreme point along -u is put `gap` beyond B's extreme point along u, so a positive gap is a
/// separating plane (the shapes are at least `gap` apart) and a small overlap makes them touch.
inline void placeAlong(const Shape& a, Pose& pose_a, Shape& b, const Pose& pose_b, const Vec3& u, double gap) {
  if (auto* plane = std::get_if<Plane>(&b)) {
    *plane = Plane(u, u.dot(support(a, pose_a, -u)) - gap);
    return;
  }
  pose_a.x += support(b, pose_b, u) + gap * u - support(a, pose_a, -u);
}

/// Signed distance of the world point p to the posed shape (negative inside) [m]. For a
/// polyhedron, the largest face-plane distance: exact inside and on the surface, a lower bound
/// outside.
inline double signedDistance(const Shape& s, const Pose& pose, const Vec3& p) {
  const Vec3 pb = pose.toBody(p);
  if (const auto* sphere = std::get_if<Sphere>(&s)) return pb.norm() - sphere->radius;
  if (const auto* box = std::get_if<Box>(&s)) {
    const Vec3 q = pb.cwiseAbs() - box->half_extents;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  }
  if (const auto* capsule = std::get_if<Capsule>(&s)) {
    const double z = std::clamp(pb.z(), -capsule->half_height, capsule->half_height);
    return (pb - Vec3(0, 0, z)).norm() - capsule->radius;
  }
  if (const auto* plane = std::get_if<Plane>(&s)) return plane->normal.dot(p) - plane->offset;
  if (const auto* poly = std::get_if<ConvexPolyhedron>(&s)) {
    double d = -1e300;
    for (std::size_t f = 0; f < poly->normals.size(); ++f) d = std::max(d, poly->normals[f].dot(pb) - poly->offsets[f]);
    return d;
  }
  return 1e300;
}

/// The overlap of the two posed shapes' projections on the unit u, B below A:
/// \f$u \cdot s_B(u) - u \cdot s_A(-u)\f$ (negative: a gap) [m]. A plane B reaches up to its offset
/// along its normal, and without bound along any other direction.
inline double overlapAlong(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, const Vec3& u) {
  if (const auto* plane = std::get_if<Plane>(&b)) {
    if ((u - plane->normal).norm() > 1e-12) return 1e300;
    return plane->offset - u.dot(support(a, pose_a, -u));
  }
  return u.dot(support(b, pose_b, u)) - u.dot(support(a, pose_a, -u));
}

/// Applies the rigid motion p -> Q p + T to a pose.
inline Pose moved(const Pose& pose, const Mat3& Q, const Vec3& T) {
  Pose p;
  p.x = Q * pose.x + T;
  p.q = (Quat(Q) * pose.q).normalized();
  return p;
}

/// Applies the rigid motion to a shape (only a plane changes: it lives in the world frame).
inline Shape moved(const Shape& s, const Mat3& Q, const Vec3& T) {
  if (const auto* plane = std::get_if<Plane>(&s)) {
    const Vec3 n = Q * plane->normal;
    return Plane(n, plane->offset + n.dot(T));
  }
  return s;
}

/// A readable description of a pair for failure messages.
inline std::string pairName(const Shape& a, const Shape& b) {
  return std::string(shapeName(a)) + " against " + shapeName(b);
}

}  // namespace physlab::test
