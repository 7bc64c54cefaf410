// Lab 2, sections 1, 2 and 4: one spring's force and Jacobians, and the ground's penalty force.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/springs.hpp"

namespace physlab {

Vec3 springForce(const Spring& spring, const Vec3& xa, const Vec3& xb, const Vec3& va,
                 const Vec3& vb) {
  // Measure the spring: l = x_a - x_b, its length and its rate of change
  const Vec3 l = xa - xb;
  const double length = l.norm();
  const Vec3 u = l / length;
  const Vec3 l_dot = va - vb;
  // Push along the spring with the elastic and damping magnitudes
  return -(spring.ks * (length - spring.rest) + spring.kd * l_dot.dot(u)) * u;
}

SpringJacobian springJacobian(const Spring& spring, const Vec3& xa, const Vec3& xb,
                              const Vec3& va, const Vec3& vb, JacobianForm form) {
  // Measure the spring as in springForce()
  const Vec3 l = xa - xb;
  const double length = l.norm();
  const Vec3 u = l / length;
  const Vec3 l_dot = va - vb;
  const Mat3 uuT = u * u.transpose();
  const Mat3 P = Mat3::Identity() - uuT;
  // Differentiate the damping part along the spring with respect to the velocities
  SpringJacobian J;
  J.dfa_dva = -spring.kd * uuT;
  // Differentiate with respect to the positions: exactly, or keeping the definite part only
  const double elastic = spring.ks * (length - spring.rest);
  if (form == JacobianForm::Exact) {
    const double s = elastic + spring.kd * l_dot.dot(u);
    J.dfa_dxa = -(spring.ks * uuT + (spring.kd / length) * u * (l_dot.transpose() * P) + (s / length) * P);
  } else {
    J.dfa_dxa = -(spring.ks * uuT + (std::max(0.0, elastic) / length) * P);
  }
  return J;
}

Vec3 groundForce(const Ground& ground, const Vec3& x, const Vec3& v) {
  // Above the ground, or with the ground switched off (stiffness 0), nothing pushes
  const double depth = ground.height - x.z();
  if (ground.stiffness == 0.0 || depth <= 0.0) return Vec3::Zero();
  // Below it a spring pushes up in proportion to the depth, and a damper resists motion in z
  return Vec3(0.0, 0.0, ground.stiffness * depth - ground.damping * v.z());
}

}  // namespace physlab
