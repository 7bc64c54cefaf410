// Lab 2, sections 1, 2 and 4: one spring's force and Jacobians, and the ground's penalty force.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"

namespace physlab {

Vec3 springForce(const Spring& spring, const Vec3& xa, const Vec3& xb, const Vec3& va,
                 const Vec3& vb) {
  // Measure the spring: l = x_a - x_b, its length and its rate of change
  // TODO(student): measure the spring: l = x_a - x_b, its length and its rate of change.
  // Push along the spring with the elastic and damping magnitudes
  // TODO(student): push along the spring with the elastic and damping magnitudes.
  notImplemented("springForce", "Lab 2 handout, section 1", spring, xa, xb, va, vb);
}

SpringJacobian springJacobian(const Spring& spring, const Vec3& xa, const Vec3& xb,
                              const Vec3& va, const Vec3& vb, JacobianForm form) {
  // Measure the spring as in springForce()
  // TODO(student): measure the spring as in springForce().
  // Differentiate the damping part along the spring with respect to the velocities
  // TODO(student): differentiate the damping part along the spring with respect to the velocities.
  // Differentiate with respect to the positions: exactly, or keeping the definite part only
  // TODO(student): differentiate with respect to the positions: exactly, or keeping the definite part only.
  notImplemented("springJacobian", "Lab 2 handout, section 2", spring, xa, xb, va, vb, form);
}

Vec3 groundForce(const Ground& ground, const Vec3& x, const Vec3& v) {
  // Above the ground nothing pushes
  // TODO(student): above the ground nothing pushes.
  // Below it a spring pushes up in proportion to the depth, and a damper resists motion in z
  // TODO(student): below it a spring pushes up in proportion to the depth, and a damper resists motion in z.
  notImplemented("groundForce", "Lab 2 handout, section 4", ground, x, v);
}

}  // namespace physlab
