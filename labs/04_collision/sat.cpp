// Lab 4, sections 5-6: the separating-axis test for boxes and convex polyhedra, clipping of the
// incident face (Sutherland-Hodgman), and reduction of the manifold to 4 points.
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {

ContactPolygon clipPolygon(const ContactPolygon& polygon, const Vec3& plane_normal, double plane_offset,
                           std::uint32_t plane_id) {
  // Refuse a count that would read past the points, and a point or plane that is not finite
  // TODO(student): validatePolygon(polygon, "clipPolygon polygon") (collision.hpp); requireFinite() (error.hpp) on
  //   plane_normal and InvalidInput unless plane_offset is finite, naming each ("clipPolygon plane_normal", ...).
  // Keep the edge's start when it is inside
  // TODO(student): for each edge (p, q) of the polygon (q the next point, cyclically): d = m . p -
  //   o; keep p when d <= 0.
  // Add the crossing when the edge passes through the plane
  // TODO(student): when d_p and d_q have strictly opposite signs, add p + d_p/(d_p - d_q) (q - p)
  //   with depth 0 and id combineFeatures(p.id, plane_id).
  notImplemented("clipPolygon", "Lab 4 handout, section 5", polygon, plane_normal, plane_offset, plane_id);
}

Manifold reduceContacts(const Vec3& normal, const ContactPolygon& candidates) {
  // Refuse a count that would read past the points, and a point or normal that is not finite
  // TODO(student): requireFinite(normal, "reduceContacts normal") (error.hpp) and validatePolygon(candidates,
  //   "reduceContacts candidates") (collision.hpp).
  // Start from the deepest point
  // TODO(student): 4 or fewer candidates are returned as they are; otherwise the largest depth.
  // Add the point farthest from it
  // TODO(student): measure distances in the plane normal to n: remove the component along n first.
  // Add the point farthest from the line through both (the largest triangle)
  // TODO(student): |((p2 - p1) x (p - p1)) . n| is twice the triangle's area.
  // Add the point outside that triangle that adds the most area to it
  // TODO(student): for each candidate, the signed area it makes with each edge of the triangle, on
  //   the side away from the triangle; keep the largest positive one (no fourth point when none is
  //   outside).
  notImplemented("reduceContacts", "Lab 4 handout, section 5", normal, candidates);
}

Manifold collideBoxBox(const Box& a, const Pose& pose_a, const Box& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Express B in A's frame once: every axis test below reads these numbers and multiplies no matrix
  // (column j of R = R_A^T R_B is b_j in A's axes; t_A, t_B are x_A - x_B in A's and B's axes)
  // TODO(student): R_A, R_B from the quaternions; R = R_A^T R_B and |R| (entry by entry); t_A =
  //   R_A^T t, t_B = R_B^T t with t = x_A - x_B.
  // Test the 6 face axes; any positive gap is a separating plane
  // (along a_k: r_A = h_A,k, r_B = sum_j |R_kj| h_B,j; along b_k the same with R's column)
  // TODO(student): overlap = r_A + r_B - |t_A,k| (|t_B,k| for b_k); return an empty manifold at the
  //   first negative one; orient the best axis so that L . (x_A - x_B) >= 0 (from B to A).
  // Test the 9 edge-pair axes, skipping (near-)parallel edges whose faces were already tested
  // (in A's frame L = e_i x (column j of R), so radii and distance are two products each; neither
  // the test nor the ranking needs |L|: g / |L| < g* / |L*| for overlaps g, g* >= 0 along the
  // unnormalised axes is g^2 |L*|^2 < g*^2 |L|^2, so only the winner is divided by |L|)
  // TODO(student): with i1, i2 = i+1, i+2 (mod 3), the same for j: |L|^2 = R_i1j^2 + R_i2j^2
  //   (skipped below 1e-12); r_A = h_A,i1 |R_i2j| + h_A,i2 |R_i1j|; r_B = h_B,j1 |R_ij2| + h_B,j2
  //   |R_ij1|; g = r_A + r_B - |t_A,i2 R_i1j - t_A,i1 R_i2j|; return empty at g < 0; remember
  //   i, j, g and |L|^2 of the best.
  // Prefer a face axis unless an edge axis is clearly shallower
  // TODO(student): use the edge axis only when its overlap g / |L| < (1 - kEdgeAxisBias) times
  //   the best face overlap.
  // Edge-edge: one point between the two edges that reach furthest towards each other
  // (on the winner's unit world axis, its depth measured along that axis: the ranking above
  // divided by a length made of R's entries, exact only for an exactly orthonormal R)
  // TODO(student): n = a_i x b_j normalised, towards A; depth = r_A + r_B - |t . n| in the world.
  //   A's edge along a_i passes through x_A + sum_{k != i} -sign(a_k . n) h_k a_k (B's:
  //   +sign(b_k . n)); closestSegmentParameters on the two edges, the point is the midpoint.
  // Face: the reference face is the winner's face towards the other box
  // TODO(student): its outward normal n_ref is -n for a face of A, n for a face of B.
  // Find the incident face: the other box's face most anti-parallel to the reference normal
  // TODO(student): the axis m of the other box with the largest |n_ref . c_m|, on the side with
  //   n_ref . (sign c_m) < 0; its 4 corners, in order around the face, with their corner numbers as
  //   ids.
  // Clip it by the four side planes of the reference face
  // TODO(student): for each of the two other axes u of the reference box, planes (u, u . x_ref +
  //   h_u) and (-u, -u . x_ref + h_u), as clipPolygon does but into small arrays on the stack (a
  //   quad clipped by 4 planes has at most 8 points; a ContactPolygon holds 64).
  // Keep the points below the reference face, at most 4
  // (moved half their depth up to the midpoint, compacted in place; reduceContacts returns 4 or
  // fewer as they are, so only a larger set pays for its 64-point candidate buffer)
  // TODO(student): depth = n_ref . (face centre) - n_ref . p; keep depth >= 0 at p + depth/2 n_ref,
  //   id combined with the reference face; empty manifold when none is kept; more than 4:
  //   reduceContacts(n, ...).
  notImplemented("collideBoxBox", "Lab 4 handout, section 5", a, pose_a, b, pose_b);
}

Manifold collideConvexConvex(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                             const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): validateShape(a, "shape a") and validatePose(pose_a, "pose_a") (collision.hpp), the same for b.
  // Move both into the world
  // TODO(student): pose.toWorld on every vertex (a std::vector each is fine here).
  // Overlap along L, oriented from B to A: the smaller of the two ways the projections overlap
  // TODO(student): with [lo, hi] the projections' ranges: min(hi_B - lo_A, hi_A - lo_B); the normal
  //   is L for the first, -L for the second.
  // Test every face normal of both; a positive gap is a separating plane
  // (one-sided: the face's own body lies below it, the other body must reach down past it)
  // TODO(student): one-sided for a face: its own body lies below it, so for a face of A overlap =
  //   hi_A - lo_B with normal -L, for a face of B hi_B - lo_A with normal L.
  // Test the cross product of every pair of edge directions
  // TODO(student): skip near-parallel pairs (|d_A x d_B| < 1e-6 |d_A||d_B|); the overlap is
  //   two-sided here.
  // Prefer a face axis unless an edge axis is clearly shallower
  // TODO(student): use the edge axis only when its overlap < (1 - kEdgeAxisBias) times the best
  //   face overlap.
  // Edge-edge: among the edges parallel to the winners, those reaching furthest across
  // TODO(student): A's edge parallel to the winning direction with the smallest n . (midpoint), B's
  //   with the largest; then closestSegmentParameters.
  // Face: the reference face's outward normal points at the other body
  // TODO(student): n_ref = the winning face's world normal.
  // Find the incident face: the other body's face most anti-parallel to the reference normal
  // TODO(student): the face with the smallest n_ref . (its world normal); its world vertices, ids =
  //   vertex indices.
  // Clip it by the side planes through the reference face's edges
  // TODO(student): for each edge (p, q) of the reference face (counter-clockwise from outside):
  //   side normal ((q - p) x n_ref) normalised, offset side . p.
  // Keep the points below the reference face, at most 4
  // TODO(student): depth = n_ref . (face centre) - n_ref . p; keep depth >= 0 at p + depth/2 n_ref,
  //   id combined with the reference face; then reduceContacts(n, ...).
  notImplemented("collideConvexConvex", "Lab 4 handout, section 6", a, pose_a, b, pose_b);
}

}  // namespace physlab
