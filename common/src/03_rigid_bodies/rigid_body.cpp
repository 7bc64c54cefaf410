// Framework half of Lab 3: descriptions, validation, state packing, diagnostics, and the
// rotation-matrix alternative. The rigid-body physics is the student's, in labs/03_rigid_bodies.
#include <Eigen/Eigenvalues>

#include <cmath>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {
namespace {

Mat3 skew(const Vec3& w) {
  Mat3 S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

}  // namespace

RigidBody::RigidBody(double mass_, const Mat3& inertia_body_) : mass(mass_), inertia_body(inertia_body_) {
  requirePositive(mass, "rigid body mass");
  requireFinite(inertia_body, "inertia tensor");
  if ((inertia_body - inertia_body.transpose()).norm() > 1e-12 * inertia_body.norm()) {
    throw InvalidInput("inertia tensor is not symmetric");
  }
  const double smallest = Eigen::SelfAdjointEigenSolver<Mat3>(inertia_body).eigenvalues().minCoeff();
  if (!(smallest > 0.0)) {
    throw InvalidInput("inertia tensor is not positive definite (smallest eigenvalue " +
                       std::to_string(smallest) + ")");
  }
  inertia_body_inv = inertia_body.inverse();
}

RigidBodySystem::RigidBodySystem(RigidBody body, std::vector<BodyForce> forces, Vec3 gravity)
    : body_(std::move(body)), forces_(std::move(forces)), gravity_(std::move(gravity)) {
  requireFinite(gravity_, "gravity");
  for (const BodyForce& f : forces_) {
    requireFinite(f.point_body, "body force point");
    requireFinite(f.force_world, "body force");
  }
}

void RigidBodySystem::project(VecX& X) const {
  if (renormalize_) X.segment<4>(3).normalize();
}

VecX RigidBodySystem::makeState(const Vec3& x, const Quat& q, const Vec3& P, const Vec3& L) const {
  requireFinite(q.coeffs(), "orientation quaternion");
  if (!(q.norm() > 0.0)) throw InvalidInput("orientation quaternion is zero");
  VecX X(13);
  const Quat u = q.normalized();
  X << x, u.w(), u.x(), u.y(), u.z(), P, L;
  validateState(X);
  return X;
}

std::vector<AppliedForce> RigidBodySystem::placedForces(const VecX& X) const {
  std::vector<AppliedForce> applied;
  const Vec3 x = X.head<3>();
  applied.reserve(forces_.size());
  const Mat3 R = orientationOf(X).normalized().toRotationMatrix();
  for (const BodyForce& f : forces_) applied.push_back({x + R * f.point_body, f.force_world});
  return applied;
}

double RigidBodySystem::kineticEnergy(const VecX& X) const {
  const Mat3 R = orientationOf(X).normalized().toRotationMatrix();
  const Vec3 P = X.segment<3>(7), L = X.segment<3>(10);
  return 0.5 * P.squaredNorm() / body_.mass + 0.5 * L.dot(R * body_.inertia_body_inv * R.transpose() * L);
}

RotationMatrixSystem::RotationMatrixSystem(RigidBody body, bool orthonormalize)
    : body_(std::move(body)), orthonormalize_(orthonormalize) {}

void RotationMatrixSystem::project(VecX& X) const {
  if (!orthonormalize_) return;
  Eigen::Map<Mat3> R(X.data() + 3);
  R = gramSchmidt(Mat3(R));
}

VecX RotationMatrixSystem::makeState(const Vec3& x, const Quat& q, const Vec3& P, const Vec3& L) const {
  requireFinite(q.coeffs(), "orientation quaternion");
  if (!(q.norm() > 0.0)) throw InvalidInput("orientation quaternion is zero");
  VecX X(18);
  X.head<3>() = x;
  Eigen::Map<Mat3>(X.data() + 3) = q.normalized().toRotationMatrix();
  X.segment<3>(12) = P;
  X.segment<3>(15) = L;
  validateState(X);
  return X;
}

double RotationMatrixSystem::kineticEnergy(const VecX& X) const {
  const Eigen::Map<const Mat3> R(X.data() + 3);
  const Vec3 P = X.segment<3>(12), L = X.segment<3>(15);
  const Vec3 omega = R * body_.inertia_body_inv * R.transpose() * L;
  return 0.5 * P.squaredNorm() / body_.mass + 0.5 * omega.dot(L);
}

double RotationMatrixSystem::orthonormalityError(const VecX& X) const {
  const Eigen::Map<const Mat3> R(X.data() + 3);
  return (R.transpose() * R - Mat3::Identity()).norm();
}

void RotationMatrixSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // The lecture's matrix form: xdot = P / M, Rdot = omega* R, with omega from the current
  // (possibly no longer orthonormal) R, exactly as a matrix integrator would see it.
  const Eigen::Map<const Mat3> R(X.data() + 3);
  const Vec3 omega = R * body_.inertia_body_inv * R.transpose() * X.segment<3>(15);
  qdot.head<3>() = X.segment<3>(12) / body_.mass;
  Eigen::Map<Mat3>(qdot.data() + 3) = skew(omega) * R;
}

void RotationMatrixSystem::computeVelocityRate(const VecX& /*X*/, Eigen::Ref<VecX> pdot) const {
  pdot.setZero();  // torque-free and force-free: P and L are constant
}

}  // namespace physlab
