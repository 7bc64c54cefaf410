/// \file rigid.hpp
/// \brief Lab 3: rigid-body state with quaternions, inertia tensors and the Newton-Euler equations.
///
/// A rigid body's state follows the lecture: position \f$x\f$ of the centre of mass, orientation
/// \f$q\f$ (unit quaternion), linear momentum \f$P\f$ and angular momentum \f$L\f$, all in the world
/// frame. As a System its flat state is
/// \f$X = [x_{(3)},\ q_{w}, q_x, q_y, q_z,\ P_{(3)},\ L_{(3)}]\f$ (13 numbers; position part
/// \f$[x, q]\f$, 7; velocity part \f$[P, L]\f$, 6). Note the quaternion is stored scalar first, as
/// Eigen's constructor Quat(w, x, y, z) takes it (not as Eigen stores its coefficients).
/// Auxiliary quantities: \f$v = P/M\f$, \f$R = R(q)\f$, \f$I^{-1} = R\, I_{body}^{-1} R^T\f$,
/// \f$\omega = I^{-1} L\f$.
#pragma once

#include <string>
#include <vector>

#include "physlab/math.hpp"
#include "physlab/system.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// The constant description of a rigid body: mass and body-frame inertia about the centre of mass.
struct RigidBody {
  /// Throws InvalidInput for a mass that is not positive and finite, or an inertia tensor that
  /// is not symmetric positive definite (naming which).
  /// \param mass M [kg]
  /// \param inertia_body \f$I_{body}\f$, body frame, about the centre of mass [kg m^2]
  RigidBody(double mass, const Mat3& inertia_body);
  double mass;            ///< M [kg]
  Mat3 inertia_body;      ///< \f$I_{body}\f$, body frame, about the centre of mass [kg m^2]
  Mat3 inertia_body_inv;  ///< \f$I_{body}^{-1}\f$ [1/(kg m^2)]
};

/// A constant force applied at a point fixed in the body.
struct BodyForce {
  Vec3 point_body;   ///< where it acts, body frame, relative to the centre of mass [m]
  Vec3 force_world;  ///< the force, world frame [N]
};

/// Total force and torque about a reference point.
struct Wrench {
  Vec3 force = Vec3::Zero();   ///< \f$F = \sum F_i\f$, world frame [N]
  Vec3 torque = Vec3::Zero();  ///< \f$\tau = \sum (p_i - x) \times F_i\f$, world frame [N m]
};

/// A force at a world point.
struct AppliedForce {
  Vec3 point;  ///< world frame [m]
  Vec3 force;  ///< world frame [N]
};

/// \name Student functions (Lab 3)
///@{

/// Inertia of a solid box of mass `M` and edge lengths `size` = (a, b, c) about its centre, body
/// axes along the edges: \f$\frac{M}{12}\mathrm{diag}(b^2 + c^2,\ a^2 + c^2,\ a^2 + b^2)\f$.
/// InvalidInput unless M and every edge are positive and finite. Handout: Lab 3, section 1.
Mat3 boxInertia(double M, const Vec3& size);
/// Inertia of a solid sphere: \f$\frac25 M r^2\,\mathbb 1\f$. InvalidInput unless M and r are
/// positive and finite. Handout: Lab 3, section 1.
Mat3 sphereInertia(double M, double radius);
/// Inertia of a solid cylinder with its axis along z:
/// \f$\mathrm{diag}(\frac{M}{12}(3r^2 + h^2),\ \frac{M}{12}(3r^2 + h^2),\ \frac12 M r^2)\f$.
/// InvalidInput unless M, r and h are positive and finite. Handout: Lab 3, section 1.
Mat3 cylinderInertia(double M, double radius, double height);
/// Inertia of point masses `m` (n) at `r` (3 x n) about their centre of mass:
/// \f$\sum_i m_i\big((r_{0i}^T r_{0i})\mathbb 1 - r_{0i} r_{0i}^T\big)\f$, \f$r_{0i} = r_i - c\f$.
/// InvalidInput when r has not m.size() columns, m is empty, a mass is not positive and finite or
/// a position not finite. Handout: Lab 3, section 1.
Mat3 pointMassInertia(const VecX& m, const Mat3X& r);
/// World angular velocity \f$\omega = R\, I_{body}^{-1} R^T L\f$ [rad/s], with R the rotation of
/// \f$q / |q|\f$: q need not have unit length (an integrated state's quaternion drifts off it
/// between renormalisations). InvalidInput when q is zero or not finite (no rotation), or L not
/// finite. Handout: Lab 3, section 2.
Vec3 angularVelocity(const RigidBody& body, const Quat& q, const Vec3& L);
/// Total force and torque about the world point `x` (the centre of mass) of forces at world
/// points: \f$F = \sum_i F_i\f$, \f$\tau = \sum_i (p_i - x) \times F_i\f$, world frame.
/// Handout: Lab 3, section 3.
Wrench wrenchAbout(const Vec3& x, const std::vector<AppliedForce>& forces);
/// Velocity of the world point `p` of a body moving with `v` and `omega` about its centre `x`:
/// \f$v + \omega \times (p - x)\f$ [m/s]. Handout: Lab 3, section 3.
Vec3 pointVelocity(const Vec3& v, const Vec3& omega, const Vec3& x, const Vec3& p);
/// The exact update for constant \f$\omega\f$ over a step: \f$q_{n+1} = \exp(\tfrac h2 \omega)\, q_n\f$,
/// i.e. a rotation by \f$|\omega| h\f$ about \f$\omega/|\omega|\f$ (q unchanged when \f$\omega = 0\f$).
/// InvalidInput when q is zero or not finite, or omega or h not finite. Handout: Lab 3, section 5.
Quat exponentialUpdate(const Quat& q, const Vec3& omega, double h);
/// Gram-Schmidt re-orthonormalisation of the columns of `R` (first column normalised, second made
/// orthogonal to it and normalised, third the cross product). Handout: Lab 3, section 6.
Mat3 gramSchmidt(const Mat3& R);
/// One explicit Euler step of the matrix form \f$\dot R = \omega^* R\f$ for a constant world-frame
/// \f$\omega\f$ [rad/s]: \f$R_{n+1} = R_n + h\,\omega^* R_n\f$, with \f$\omega^*\f$ the cross-product
/// matrix (\f$\omega^* a = \omega \times a\f$), followed by gramSchmidt() when `orthonormalize`.
/// Handout: Lab 3, section 6.
Mat3 rotationMatrixStep(const Mat3& R, const Vec3& omega, double h, bool orthonormalize);
/// Euler's equations in the body frame: \f$\dot\omega = I^{-1}(\tau - \omega \times I\omega)\f$ with
/// \f$I = I_{body}\f$, \f$\omega\f$ and \f$\tau\f$ in body coordinates [rad/s^2]. Handout: Lab 3, section 7.
Vec3 bodyFrameOmegaRate(const Mat3& I_body, const Vec3& omega_body, const Vec3& torque_body);
///@}

/// One rigid body under constant body-fixed forces and uniform gravity, as a System.
class RigidBodySystem final : public System {
 public:
  /// \param body mass and inertia
  /// \param forces forces fixed in the body (may be empty)
  /// \param gravity uniform gravitational acceleration, world frame [m/s^2]
  RigidBodySystem(RigidBody body, std::vector<BodyForce> forces = {}, Vec3 gravity = Vec3::Zero());
  /// 7: \f$x\f$ and \f$q = (q_w, q_x, q_y, q_z)\f$.
  Index positionSize() const override { return 7; }
  /// 6: \f$P\f$ and \f$L\f$.
  Index velocitySize() const override { return 6; }
  /// "rigid body".
  std::string name() const override { return "rigid body"; }
  const RigidBody& body() const { return body_; }  ///< the description
  /// Turns quaternion renormalisation after each step on (default) or off.
  void setRenormalize(bool on) { renormalize_ = on; }
  /// Whether project() renormalises q.
  bool renormalize() const { return renormalize_; }
  /// Renormalises q when renormalisation is on.
  void project(VecX& X) const override;
  /// Packs a state; throws InvalidInput for a zero or non-finite quaternion or non-finite vectors.
  /// The quaternion is normalised.
  VecX makeState(const Vec3& x, const Quat& q, const Vec3& P, const Vec3& L) const;
  /// The body-fixed forces at their current world points \f$p = x + R\,r_{body}\f$; empty (no
  /// allocation) for a body without any. Gravity is not among them: it acts at the centre of
  /// mass, so the derivative adds \f$M g\f$ to the force directly (it has no torque).
  std::vector<AppliedForce> appliedForces(const VecX& X) const {
    return forces_.empty() ? std::vector<AppliedForce>() : placedForces(X);
  }
  /// Kinetic energy \f$\frac{|P|^2}{2M} + \frac12 L^T I^{-1} L\f$ [J] (with the normalised q).
  double kineticEnergy(const VecX& X) const;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;

 private:
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the derivative remotely
  // appliedForces() of a body with body-fixed forces
  std::vector<AppliedForce> placedForces(const VecX& X) const;
  RigidBody body_;
  std::vector<BodyForce> forces_;
  Vec3 gravity_;
  bool renormalize_ = true;
};

/// The orientation of a rigid-body state, \f$q\f$ (not normalised). Inline: every derivative
/// evaluation reads it.
inline Quat orientationOf(const VecX& X) { return Quat(X[3], X[4], X[5], X[6]); }

/// The alternative the lecture compares: a torque-free body whose orientation is a rotation
/// matrix, \f$X = [x_{(3)},\ R_{(9, column-major)},\ P_{(3)},\ L_{(3)}]\f$, with
/// \f$\dot R = \omega^* R\f$ and optional Gram-Schmidt (gramSchmidt()) after each step.
class RotationMatrixSystem final : public System {
 public:
  /// \param body mass and inertia; \param orthonormalize apply Gram-Schmidt after each step
  RotationMatrixSystem(RigidBody body, bool orthonormalize);
  /// 12: \f$x\f$ and the 9 entries of \f$R\f$.
  Index positionSize() const override { return 12; }
  /// 6: \f$P\f$ and \f$L\f$.
  Index velocitySize() const override { return 6; }
  /// "rigid body (rotation matrix)".
  std::string name() const override { return "rigid body (rotation matrix)"; }
  /// Applies gramSchmidt() to R when enabled.
  void project(VecX& X) const override;
  /// Packs a state with orientation R(q) (q normalised first); throws InvalidInput for a zero or
  /// non-finite quaternion or non-finite vectors.
  VecX makeState(const Vec3& x, const Quat& q, const Vec3& P, const Vec3& L) const;
  /// Kinetic energy \f$\frac{|P|^2}{2M} + \frac12 \omega \cdot L\f$ with \f$\omega = R I_{body}^{-1} R^T L\f$ [J].
  double kineticEnergy(const VecX& X) const;
  /// \f$\lVert R^T R - \mathbb 1\rVert\f$: how far R has drifted from a rotation.
  double orthonormalityError(const VecX& X) const;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;

 private:
  RigidBody body_;
  bool orthonormalize_;
};

}  // namespace physlab
