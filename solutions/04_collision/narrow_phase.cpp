// Lab 4, sections 2-4 and 7: contacts of spheres, capsules, boxes and planes, closest points of
// segments, and the triangle-triangle test.
#include <algorithm>
#include <cmath>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

// Two balls (centre, radius): the one contact of spheres, capsules and their pairs.
Manifold ballContact(const Vec3& ca, double ra, const Vec3& cb, double rb, std::uint32_t id) {
  Manifold m;
  const Vec3 d = ca - cb;
  const double gap = d.norm();
  const double depth = ra + rb - gap;
  if (depth < 0.0) return m;
  m.normal = gap > 0.0 ? Vec3(d / gap) : Vec3::UnitZ();
  // A's deepest point is ca - ra n, B's is cb + rb n: report their midpoint
  m.add(0.5 * (ca - ra * m.normal + cb + rb * m.normal), depth, id);
  return m;
}

// The point of segment [p, q] closest to c.
Vec3 closestOnSegment(const Vec3& p, const Vec3& q, const Vec3& c) {
  const Vec3 d = q - p;
  const double t = std::clamp((c - p).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return p + t * d;
}

// Whether the segment [p, q] crosses the plane of triangle (a, b, c) at a point of the triangle.
bool segmentPiercesTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double sp = n.dot(p - a), sq = n.dot(q - a);
  if ((sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) || sp == sq) return false;
  const Vec3 x = p + sp / (sp - sq) * (q - p);
  return n.dot((b - a).cross(x - a)) >= 0.0 && n.dot((c - b).cross(x - b)) >= 0.0 &&
         n.dot((a - c).cross(x - c)) >= 0.0;
}

}  // namespace

Manifold collideSphereSphere(const Sphere& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  // Compare the distance of the centres with the sum of the radii
  return ballContact(pose_a.x, a.radius, pose_b.x, b.radius, 0);
}

Manifold collideSpherePlane(const Sphere& a, const Pose& pose_a, const Plane& b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  Manifold m;
  // Measure the centre's height above the plane
  const double height = b.normal.dot(pose_a.x) - b.offset;
  const double depth = a.radius - height;
  if (depth < 0.0) return m;
  // Put the point midway between the sphere's lowest point and the plane
  m.normal = b.normal;
  m.add(pose_a.x - 0.5 * (a.radius + height) * b.normal, depth, 0);
  return m;
}

Manifold collideSphereBox(const Sphere& a, const Pose& pose_a, const Box& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  Manifold m;
  // Clamp the centre, in the box frame, to the box
  const Vec3& h = b.half_extents;
  const Vec3 c = pose_b.toBody(pose_a.x);
  const Vec3 closest = c.cwiseMax(-h).cwiseMin(h);
  Vec3 normal_body, on_box;
  double depth;
  if (closest != c) {
    // Outside: the normal runs from the closest point to the centre
    const Vec3 d = c - closest;
    const double gap = d.norm();
    depth = a.radius - gap;
    if (depth < 0.0) return m;
    normal_body = d / gap;
    on_box = closest;
  } else {
    // Inside: leave through the nearest face
    const Vec3 room = h - c.cwiseAbs();
    Index i;
    room.minCoeff(&i);
    normal_body = Vec3::Zero();
    normal_body[i] = c[i] >= 0.0 ? 1.0 : -1.0;
    on_box = c;
    on_box[i] = normal_body[i] * h[i];
    depth = a.radius + room[i];
  }
  // Put the point midway between the sphere's deepest point and the box's surface
  m.normal = pose_b.q * normal_body;
  m.add(pose_b.toWorld(0.5 * (c - a.radius * normal_body + on_box)), depth, 0);
  return m;
}

std::array<double, 2> closestSegmentParameters(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  // Refuse ends that are not finite: every parameter would be NaN
  requireFinite(p1, "segment end p1");
  requireFinite(q1, "segment end q1");
  requireFinite(p2, "segment end p2");
  requireFinite(q2, "segment end q2");
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  // Handle segments that are single points
  if (a <= 0.0 && e <= 0.0) return {0.0, 0.0};
  if (a <= 0.0) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= 0.0) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  // Minimise |p1 + s d1 - p2 - t d2|^2 over s for the lines, clamped to [0, 1]
  const double b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  // Find t for that s, and when t leaves [0, 1] clamp it and recompute s
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

Manifold collideCapsuleSphere(const Capsule& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  // Find the point of the core segment closest to the sphere's centre
  const std::array<Vec3, 2> ends = a.segment(pose_a);
  const Vec3 core = closestOnSegment(ends[0], ends[1], pose_b.x);
  // Treat it as a sphere of the capsule's radius
  return ballContact(core, a.radius, pose_b.x, b.radius, 0);
}

Manifold collideCapsuleCapsule(const Capsule& a, const Pose& pose_a, const Capsule& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  const std::array<Vec3, 2> ea = a.segment(pose_a), eb = b.segment(pose_b);
  const Vec3 da = ea[1] - ea[0], db = eb[1] - eb[0];
  // Parallel cores: one contact at each end of their overlap, so that a capsule can lie still
  if (da.cross(db).squaredNorm() <= 1e-12 * da.squaredNorm() * db.squaredNorm()) {
    const double t0 = (eb[0] - ea[0]).dot(da) / da.squaredNorm(), t1 = (eb[1] - ea[0]).dot(da) / da.squaredNorm();
    const double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(1.0, std::max(t0, t1));
    if (hi - lo > 1e-9) {
      Manifold m;
      for (std::uint32_t k = 0; k < 2; ++k) {
        const Vec3 pa = ea[0] + (k == 0 ? lo : hi) * da;
        const Manifold one = ballContact(pa, a.radius, closestOnSegment(eb[0], eb[1], pa), b.radius, k + 1);
        if (one.empty()) return Manifold{};
        m.normal = one.normal;
        m.add(one.points[0].position, one.points[0].depth, k + 1);
      }
      return m;
    }
  }
  // Otherwise the closest points of the two cores act as two spheres
  const std::array<double, 2> st = closestSegmentParameters(ea[0], ea[1], eb[0], eb[1]);
  return ballContact(ea[0] + st[0] * da, a.radius, eb[0] + st[1] * db, b.radius, 0);
}

Manifold collideBoxPlane(const Box& a, const Pose& pose_a, const Plane& b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  // Collect every corner below the plane, midway between it and the plane
  ContactPolygon below;
  for (std::uint32_t i = 0; i < 8; ++i) {
    const Vec3& h = a.half_extents;
    const Vec3 corner = pose_a.toWorld(Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
    const double height = b.normal.dot(corner) - b.offset;
    if (height <= 0.0) below.add(corner - 0.5 * height * b.normal, -height, i);
  }
  if (below.count == 0) return Manifold{};
  // Keep at most 4 of them
  return reduceContacts(b.normal, below);
}

bool trianglesIntersect(const Triangle& a, const Pose& pose_a, const Triangle& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  std::array<Vec3, 3> p, q;
  for (int i = 0; i < 3; ++i) {
    p[i] = pose_a.toWorld(a.corners[i]);
    q[i] = pose_b.toWorld(b.corners[i]);
  }
  // Look for an edge of either triangle that pierces the other: intersecting triangles have
  // two such edges (two of one, or one of each)
  for (int i = 0; i < 3; ++i) {
    if (segmentPiercesTriangle(p[i], p[(i + 1) % 3], q[0], q[1], q[2])) return true;
    if (segmentPiercesTriangle(q[i], q[(i + 1) % 3], p[0], p[1], p[2])) return true;
  }
  return false;
}

}  // namespace physlab
