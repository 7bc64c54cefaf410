// Lab 3, sections 2-4: angular velocity, forces and torques, and the rigid body's derivative.
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Vec3 angularVelocity(const RigidBody& body, const Quat& q, const Vec3& L) {
  // Refuse a quaternion that stands for no rotation
  // TODO(student): InvalidInput when q is zero or not finite, or L is not finite.
  // Rotate the body-frame inverse inertia into the world: I^-1 = R I_body^-1 R^T
  // TODO(student): R = q.normalized().toRotationMatrix(); body.inertia_body_inv is I_body^-1.
  // Apply it to the angular momentum
  // TODO(student): omega = R (I_body^-1 (R^T L)): three matrix-vector products, no 3x3 product needed.
  notImplemented("angularVelocity", "Lab 3 handout, section 2", body, q, L);
}

Wrench wrenchAbout(const Vec3& x, const std::vector<AppliedForce>& forces) {
  // Sum the forces and their moments (p - x) x F about x
  // TODO(student): each entry is (F, p): add F to the force and (p - x).cross(F) to the torque; return {F, tau}.
  notImplemented("wrenchAbout", "Lab 3 handout, section 3", x, forces);
}

Vec3 pointVelocity(const Vec3& v, const Vec3& omega, const Vec3& x, const Vec3& p) {
  // Add the rotation's velocity omega x (p - x) to the centre's velocity
  // TODO(student): return v + omega.cross(p - x).
  notImplemented("pointVelocity", "Lab 3 handout, section 3", v, omega, x, p);
}

void RigidBodySystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // Move the centre with v = P / M
  // TODO(student): qdot.head<3>() = P / M, P = X.segment<3>(7).
  // Turn the orientation with qdot = 1/2 (0, omega) q, written out as a quaternion product
  // TODO(student): omega from angularVelocity(body_, orientationOf(X), L); Quat(0, omega) * q; store w, x, y, z halves in qdot.segment<4>(3).
  notImplemented("RigidBodySystem::computePositionRate", "Lab 3 handout, section 4", X, qdot);
}

void RigidBodySystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  // Total force and torque about the centre of mass: Pdot = F, Ldot = tau (zero, with no sum to
  // do, for a body without body-fixed forces), gravity adding M g at the centre (no torque)
  // TODO(student): w = Wrench() if forces_ is empty, else wrenchAbout(X.head<3>(), appliedForces(X)); pdot = [F + M g; tau] (body_.mass, gravity_).
  notImplemented("RigidBodySystem::computeVelocityRate", "Lab 3 handout, section 4", X, pdot);
}

}  // namespace physlab
