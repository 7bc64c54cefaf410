// Lab 4, section 9: the time of impact of two moving bodies within a step, by bisection on the
// overlap test and by conservative advancement on the distance.
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {

ToiResult toiBisection(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                       const Pose& pose_b, const Motion& motion_b, double h, double tolerance) {
  // Refuse a step or tolerance that is not positive: the bracket could never get short enough
  // TODO(student): requirePositive() on h and on tolerance, naming each ("time step h", "tolerance").
  // Refuse bad shapes, poses and motions here, naming them, rather than at some later time's query
  // TODO(student): validateShape(a, "shape a"), validatePose(pose_a, "pose_a"), validateMotion(motion_a, "motion_a")
  //   (collision.hpp), the same for b.
  // Bound how fast any point can approach: the relative speed plus the spin of the far points
  // TODO(student): approachSpeedBound() along the relative velocity's direction gives |v_B - v_A| +
  //   |omega_A| rho_A + |omega_B| rho_B.
  // Sample the step finely enough that a thin shape cannot be skipped
  // TODO(student): N = ceil(mu h / (innerRadius(A) + innerRadius(B))), clamped to [1, 4096], and 1
  //   when mu h is 0 (two triangles have inner radii 0: 0 / 0); test overlap (distance().overlap at
  //   the advance()d poses) at 0 and at k h / N, counting every test in queries.
  // Halve the bracket [lo, hi] (apart at lo, overlapping at hi) until it is short enough
  // TODO(student): while mu (hi - lo) > tolerance: test the midpoint; report lo (still apart).
  notImplemented("toiBisection", "Lab 4 handout, section 9", a, pose_a, motion_a, b, pose_b, motion_b, h, tolerance);
}

ToiResult toiConservativeAdvancement(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                                     const Pose& pose_b, const Motion& motion_b, double h, double tolerance) {
  // Refuse a step or tolerance that is not positive: the bracket could never get short enough
  // TODO(student): requirePositive() on h and on tolerance, naming each ("time step h", "tolerance").
  // Refuse bad shapes, poses and motions here, naming them, rather than at some later time's query
  // TODO(student): validateShape(a, "shape a"), validatePose(pose_a, "pose_a"), validateMotion(motion_a, "motion_a")
  //   (collision.hpp), the same for b.
  // Measure the distance and the direction of the closest points at t
  // TODO(student): distance() at advance(pose, motion, t) for both; a hit when it overlaps or is <=
  //   tolerance; n = (point_a - point_b) normalised.
  // No point closes the gap faster than mu along n: advance by d / mu
  // TODO(student): mu = approachSpeedBound(..., n); no hit when mu <= 0 or when t + d / mu passes
  //   h.
  notImplemented("toiConservativeAdvancement", "Lab 4 handout, section 9", a, pose_a, motion_a, b, pose_b, motion_b, h, tolerance);
}

}  // namespace physlab
