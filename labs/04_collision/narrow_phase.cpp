// Lab 4, sections 2-4 and 7: contacts of spheres, capsules, boxes and planes, closest points of
// segments, and the triangle-triangle test.
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {

Manifold collideSphereSphere(const Sphere& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Compare the distance of the centres with the sum of the radii
  // TODO(student): depth = r_A + r_B - |x_A - x_B|; none when negative. Normal (x_A - x_B)/|x_A -
  //   x_B| (+z if the centres coincide); position = midpoint of x_A - r_A n and x_B + r_B n; id 0.
  notImplemented("collideSphereSphere", "Lab 4 handout, section 2", a, pose_a, b, pose_b);
}

Manifold collideSpherePlane(const Sphere& a, const Pose& pose_a, const Plane& b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a"), validatePose(pose_a, "pose_a") and validateShape(b, "shape b")
  //   (collision.hpp); the plane has no pose.
  // Measure the centre's height above the plane
  // TODO(student): height = n . x - d; depth = r - height, none when negative.
  // Put the point midway between the sphere's lowest point and the plane
  // TODO(student): normal = the plane's n; the lowest point is x - r n, the plane point below the
  //   centre x - height n.
  notImplemented("collideSpherePlane", "Lab 4 handout, section 2", a, pose_a, b);
}

Manifold collideSphereBox(const Sphere& a, const Pose& pose_a, const Box& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Clamp the centre, in the box frame, to the box
  // TODO(student): c = pose_b.toBody(x_A); closest = c clamped component-wise to [-h, h] (cwiseMax,
  //   cwiseMin).
  // Outside: the normal runs from the closest point to the centre
  // TODO(student): when closest != c: gap = |c - closest|, depth = r - gap (none when negative),
  //   body-frame normal (c - closest)/gap.
  // Inside: leave through the nearest face
  // TODO(student): otherwise the face with the least room h_i - |c_i|: normal sign(c_i) e_i, depth
  //   r + room, surface point c with c_i moved to the face.
  // Put the point midway between the sphere's deepest point and the box's surface
  // TODO(student): in the box frame: midpoint of c - r n and the surface point; rotate the normal
  //   and the point into the world with pose_b.
  notImplemented("collideSphereBox", "Lab 4 handout, section 2", a, pose_a, b, pose_b);
}

std::array<double, 2> closestSegmentParameters(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  // Refuse ends that are not finite: every parameter would be NaN
  // TODO(student): requireFinite() (error.hpp) on each end, naming it: "segment end p1", ..., "segment end q2".
  // Handle segments that are single points
  // TODO(student): with d1 = q1 - p1, d2 = q2 - p2: when |d1| or |d2| is 0 only one parameter is
  //   free (project and clamp).
  // Minimise |p1 + s d1 - p2 - t d2|^2 over s for the lines, clamped to [0, 1]
  // TODO(student): setting both partial derivatives to 0 gives s = (b f - c e) / (a e - b^2) with a
  //   = d1.d1, b = d1.d2, c = d1.r, e = d2.d2, f = d2.r, r = p1 - p2 (use s = 0 for parallel lines).
  // Find t for that s, and when t leaves [0, 1] clamp it and recompute s
  // TODO(student): t = (b s + f) / e; if t < 0 or t > 1, clamp t and take s = clamp((b t - c) / a,
  //   0, 1).
  notImplemented("closestSegmentParameters", "Lab 4 handout, section 3", p1, q1, p2, q2);
}

Manifold collideCapsuleSphere(const Capsule& a, const Pose& pose_a, const Sphere& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Find the point of the core segment closest to the sphere's centre
  // TODO(student): capsule.segment(pose) gives the two ends; project the centre on the segment and
  //   clamp the parameter to [0, 1].
  // Treat it as a sphere of the capsule's radius
  // TODO(student): then it is sphere-sphere between that point (radius r_A) and the sphere.
  notImplemented("collideCapsuleSphere", "Lab 4 handout, section 3", a, pose_a, b, pose_b);
}

Manifold collideCapsuleCapsule(const Capsule& a, const Pose& pose_a, const Capsule& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Parallel cores: one contact at each end of their overlap, so that a capsule can lie still
  // TODO(student): when |d_A x d_B|^2 <= 1e-12 |d_A|^2 |d_B|^2, project B's ends on A's segment; if
  //   the overlap [lo, hi] of parameters is longer than 1e-9, a ball contact at each end (ids 1 and
  //   2), each against the closest point of B's segment.
  // Otherwise the closest points of the two cores act as two spheres
  // TODO(student): closestSegmentParameters gives s, t; then sphere-sphere between the two points
  //   (id 0).
  notImplemented("collideCapsuleCapsule", "Lab 4 handout, section 3", a, pose_a, b, pose_b);
}

Manifold collideBoxPlane(const Box& a, const Pose& pose_a, const Plane& b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a"), validatePose(pose_a, "pose_a") and validateShape(b, "shape b")
  //   (collision.hpp); the plane has no pose.
  // Collect every corner below the plane, midway between it and the plane
  // TODO(student): corner i = (+-h_x, +-h_y, +-h_z) with bit k of i set for the + side; height = n
  //   . p - d; when height <= 0 add p - height/2 n with depth -height and id i to a ContactPolygon.
  // Keep at most 4 of them
  // TODO(student): reduceContacts(n, candidates); an empty manifold when no corner is below.
  notImplemented("collideBoxPlane", "Lab 4 handout, section 4", a, pose_a, b);
}

bool trianglesIntersect(const Triangle& a, const Pose& pose_a, const Triangle& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Look for an edge of either triangle that pierces the other: intersecting triangles have
  // two such edges (two of one, or one of each)
  // TODO(student): for each edge [p, q]: signed distances of p and q to the other triangle's plane
  //   must differ in sign; the crossing point x = p + s_p/(s_p - s_q)(q - p) must be inside the
  //   triangle (same side of all three edges, via cross products with its normal).
  notImplemented("trianglesIntersect", "Lab 4 handout, section 7", a, pose_a, b, pose_b);
}

}  // namespace physlab
