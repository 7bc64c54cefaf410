// Lab 4, section 8: the distance between convex shapes by GJK (Gilbert-Johnson-Keerthi).
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {

DistanceResult gjkDistance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  // TODO(student): after refusing planes: validateShape(a, "shape a") and validatePose(pose_a, "pose_a")
  //   (collision.hpp), the same for b.
  // Start from the support point along the line of centres
  // TODO(student): a simplex vertex is w = s_A(-d) - s_B(d) from coreSupport(), stored with both
  //   support points; refuse planes (InvalidInput).
  // Stop when the origin is (within round-off) in the simplex
  // TODO(student): |v|^2 tiny relative to the largest |w|^2 seen means overlap.
  // Ask for the support point against v; stop when it brings the bound no closer
  // TODO(student): w = s_A(-v) - s_B(v); converged when |v|^2 - v . w <= 1e-10 |v|^2, or when w is
  //   already in the simplex.
  // Add it and keep the sub-simplex nearest the origin
  // TODO(student): closest point of a segment, triangle (Voronoi regions) or tetrahedron (origin
  //   inside: overlap) with barycentric weights; stop if |v| did not shrink.
  // Read the closest points from the barycentric weights, then grow the cores by the margins
  // TODO(student): p_A = sum lambda_i a_i, p_B = sum lambda_i b_i; distance = |v| - margin(A) -
  //   margin(B) (overlap when <= 0); move p_A by -r_A n and p_B by +r_B n, n = v/|v|.
  notImplemented("gjkDistance", "Lab 4 handout, section 8", a, pose_a, b, pose_b);
}

}  // namespace physlab
