// Lab 3, sections 2-4: angular velocity, forces and torques, and the rigid body's derivative.
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Vec3 angularVelocity(const RigidBody& body, const Quat& q, const Vec3& L) {
  // Refuse a quaternion that stands for no rotation
  requireFinite(q.coeffs(), "angularVelocity quaternion q");
  if (!(q.squaredNorm() > 0.0)) throw InvalidInput("angularVelocity quaternion q is zero: it stands for no rotation");
  requireFinite(L, "angularVelocity angular momentum L");
  // Rotate the body-frame inverse inertia into the world: I^-1 = R I_body^-1 R^T
  const Mat3 R = q.normalized().toRotationMatrix();
  // Apply it to the angular momentum
  return R * (body.inertia_body_inv * (R.transpose() * L));
}

Wrench wrenchAbout(const Vec3& x, const std::vector<AppliedForce>& forces) {
  Wrench w;
  // Sum the forces and their moments (p - x) x F about x
  for (const AppliedForce& f : forces) {
    w.force += f.force;
    w.torque += (f.point - x).cross(f.force);
  }
  return w;
}

Vec3 pointVelocity(const Vec3& v, const Vec3& omega, const Vec3& x, const Vec3& p) {
  // Add the rotation's velocity omega x (p - x) to the centre's velocity
  return v + omega.cross(p - x);
}

void RigidBodySystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // Move the centre with v = P / M
  qdot.head<3>() = X.segment<3>(7) / body_.mass;
  // Turn the orientation with qdot = 1/2 (0, omega) q, written out as a quaternion product
  const Quat q = orientationOf(X);
  const Vec3 omega = angularVelocity(body_, q, X.segment<3>(10));
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  const Quat product = w * q;
  qdot.segment<4>(3) << 0.5 * product.w(), 0.5 * product.x(), 0.5 * product.y(), 0.5 * product.z();
}

void RigidBodySystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  // Total force and torque about the centre of mass: Pdot = F, Ldot = tau (zero, with no sum to
  // do, for a body without body-fixed forces), gravity adding M g at the centre (no torque)
  const Wrench w = forces_.empty() ? Wrench() : wrenchAbout(X.head<3>(), appliedForces(X));
  pdot.head<3>() = w.force + body_.mass * gravity_;
  pdot.tail<3>() = w.torque;
}

}  // namespace physlab
