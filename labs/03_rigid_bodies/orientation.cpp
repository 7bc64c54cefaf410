// Lab 3, sections 5-7: the alternatives to integrating qdot - an exact quaternion update, the
// rotation matrix kept orthonormal, and Euler's equations in the body frame.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

Quat exponentialUpdate(const Quat& q, const Vec3& omega, double h) {
  // Refuse a quaternion that stands for no rotation, and non-finite input
  // TODO(student): InvalidInput when q is zero or not finite, or omega or h is not finite.
  // Find the angle |omega| h turned in the step
  // TODO(student): return q unchanged when it is zero.
  // Rotate by it about omega's direction: exp(h omega / 2) q
  // TODO(student): Quat(Eigen::AngleAxisd(angle, axis)) * q.
  notImplemented("exponentialUpdate", "Lab 3 handout, section 5", q, omega, h);
}

Mat3 gramSchmidt(const Mat3& R) {
  // Normalise the first column
  // TODO(student): Q.col(0) = R.col(0).normalized().
  // Remove its component from the second column and normalise
  // TODO(student): subtract (Q0 . R1) Q0 from R.col(1), then normalise.
  // Complete a right-handed frame with the cross product
  // TODO(student): Q.col(2) = Q.col(0).cross(Q.col(1)).
  notImplemented("gramSchmidt", "Lab 3 handout, section 6", R);
}

Mat3 rotationMatrixStep(const Mat3& R, const Vec3& omega, double h, bool orthonormalize) {
  // Build the cross-product matrix omega*, so that omega* a = omega x a
  // TODO(student): rows (0, -wz, wy), (wz, 0, -wx), (-wy, wx, 0).
  // Take the explicit Euler step R + h omega* R
  // TODO(student): store it in a Mat3, not in auto (an Eigen expression).
  // Pull the result back onto the rotations when asked
  // TODO(student): return gramSchmidt(next) when orthonormalize, next otherwise.
  notImplemented("rotationMatrixStep", "Lab 3 handout, section 6", R, omega, h, orthonormalize);
}

Vec3 bodyFrameOmegaRate(const Mat3& I_body, const Vec3& omega_body, const Vec3& torque_body) {
  // Subtract the gyroscopic term omega x I omega from the torque and divide by I
  // TODO(student): solve I wdot = tau - omega x (I omega), e.g. with I.ldlt().solve(...).
  notImplemented("bodyFrameOmegaRate", "Lab 3 handout, section 7", I_body, omega_body, torque_body);
}

}  // namespace physlab
