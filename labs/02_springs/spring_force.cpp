// Lab 2, sections 1, 2 and 4: one spring's force and Jacobians, and the ground's penalty force.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"

namespace physlab {

Vec3 springForce(const Spring& spring, const Vec3& xa, const Vec3& xb, const Vec3& va,
                 const Vec3& vb) {
  // Measure the spring: l = x_a - x_b, its length and its rate of change
  // TODO(student): l, |l|, u = l/|l| and l_dot = v_a - v_b.
  // Push along the spring with the elastic and damping magnitudes
  // TODO(student): return -(ks (|l| - r) + kd l_dot.u) u.
  notImplemented("springForce", "Lab 2 handout, section 1", spring, xa, xb, va, vb);
}

SpringJacobian springJacobian(const Spring& spring, const Vec3& xa, const Vec3& xb,
                              const Vec3& va, const Vec3& vb, JacobianForm form) {
  // Measure the spring as in springForce()
  // TODO(student): l, |l|, u, l_dot, and the projector P = I - u u^T.
  // Differentiate the damping part along the spring with respect to the velocities
  // TODO(student): dfa_dva = -kd u u^T.
  // Differentiate with respect to the positions: exactly, or keeping the definite part only
  // TODO(student): see section 2 for both forms; the definite one uses max(0, ks (|l| - r)).
  notImplemented("springJacobian", "Lab 2 handout, section 2", spring, xa, xb, va, vb, form);
}

Vec3 groundForce(const Ground& ground, const Vec3& x, const Vec3& v) {
  // Above the ground, or with the ground switched off (stiffness 0), nothing pushes
  // TODO(student): depth d = height - z; return zero when d <= 0 (touching is not contact) or
  // when ground.stiffness is 0 (the damper too is off then).
  // Below it a spring pushes up in proportion to the depth, and a damper resists motion in z
  // TODO(student): (0, 0, k d - c v_z).
  notImplemented("groundForce", "Lab 2 handout, section 4", ground, x, v);
}

}  // namespace physlab
