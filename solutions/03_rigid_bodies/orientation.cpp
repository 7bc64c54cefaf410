// Lab 3, sections 5-7: the alternatives to integrating qdot - an exact quaternion update, the
// rotation matrix kept orthonormal, and Euler's equations in the body frame.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Quat exponentialUpdate(const Quat& q, const Vec3& omega, double h) {
  // Refuse a quaternion that stands for no rotation, and non-finite input
  requireFinite(q.coeffs(), "exponentialUpdate quaternion q");
  if (!(q.squaredNorm() > 0.0)) throw InvalidInput("exponentialUpdate quaternion q is zero: it stands for no rotation");
  requireFinite(omega, "exponentialUpdate angular velocity omega");
  if (!std::isfinite(h)) throw InvalidInput("exponentialUpdate step h must be finite, got " + std::to_string(h));
  // Find the angle |omega| h turned in the step
  const double angle = omega.norm() * h;
  if (angle == 0.0) return q;
  // Rotate by it about omega's direction: exp(h omega / 2) q
  const Quat turn(Eigen::AngleAxisd(angle, omega.normalized()));
  return turn * q;
}

Mat3 gramSchmidt(const Mat3& R) {
  Mat3 Q;
  // Normalise the first column
  Q.col(0) = R.col(0).normalized();
  // Remove its component from the second column and normalise
  Q.col(1) = (R.col(1) - Q.col(0).dot(R.col(1)) * Q.col(0)).normalized();
  // Complete a right-handed frame with the cross product
  Q.col(2) = Q.col(0).cross(Q.col(1));
  return Q;
}

Mat3 rotationMatrixStep(const Mat3& R, const Vec3& omega, double h, bool orthonormalize) {
  // Build the cross-product matrix omega*, so that omega* a = omega x a
  Mat3 omega_star;
  omega_star << 0.0, -omega.z(), omega.y(), omega.z(), 0.0, -omega.x(), -omega.y(), omega.x(), 0.0;
  // Take the explicit Euler step R + h omega* R
  const Mat3 next = R + h * omega_star * R;
  // Pull the result back onto the rotations when asked
  return orthonormalize ? gramSchmidt(next) : next;
}

Vec3 bodyFrameOmegaRate(const Mat3& I_body, const Vec3& omega_body, const Vec3& torque_body) {
  // Subtract the gyroscopic term omega x I omega from the torque and divide by I
  return I_body.ldlt().solve(torque_body - omega_body.cross(I_body * omega_body));
}

}  // namespace physlab
