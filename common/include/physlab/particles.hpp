/// \file particles.hpp
/// \brief Lab 1: particle systems and the forces between particles.
///
/// A particle system of \f$n\f$ particles has state \f$X = [x_1 \dots x_n,\ v_1 \dots v_n]\f$
/// (all positions, then all velocities; world frame; metres and metres per second), so the
/// positions are the first \f$3n\f$ entries and read as a 3 x n matrix with positions(). Its
/// derivative is \f$\dot X = [v_1 \dots v_n,\ F_1/m_1 \dots F_n/m_n]\f$ where each \f$F_i\f$
/// is the sum of every Force's contribution ("forces accumulate"); a force that is a uniform
/// acceleration (gravity) is added as that acceleration after the division.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physlab/math.hpp"
#include "physlab/system.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// Positions \f$x_1 \dots x_n\f$ of a particle state as a 3 x n view (world frame, m).
inline ConstPoints positions(const VecX& X) { return ConstPoints(X.data(), 3, X.size() / 6); }
/// Velocities \f$v_1 \dots v_n\f$ of a particle state as a 3 x n view (world frame, m/s).
inline ConstPoints velocities(const VecX& X) {
  return ConstPoints(X.data() + X.size() / 2, 3, X.size() / 6);
}

/// What a force sees of the particles: positions, velocities and masses.
struct ParticleView {
  ConstPoints x;   ///< positions, 3 x n, world frame [m]
  ConstPoints v;   ///< velocities, 3 x n, world frame [m/s]
  const VecX& m;   ///< masses, n [kg]; +infinity marks a pinned particle
};

/// A force acting on particles. Forces are constant descriptions: they hold parameters, never
/// state.
class Force {
 public:
  virtual ~Force() = default;
  /// Short name for reports ("uniform gravity", "damped spring", ...).
  virtual std::string name() const = 0;
  /// Add this force's contribution to each particle's total force, `F` (3 x n, N).
  virtual void accumulate(const ParticleView& s, Points F) const = 0;
  /// The potential energy \f$U\f$ whose negative gradient is the conservative part of this
  /// force [J]; 0 for a purely dissipative force.
  virtual double potential(const ParticleView& s) const = 0;
  /// Add \f$\partial F/\partial x\f$ and \f$\partial F/\partial v\f$ (each 3n x 3n, world frame)
  /// and return true, or return false when this force offers no analytic Jacobian (the default).
  virtual bool addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const;
  /// The constant acceleration \f$a\f$ this force gives every free particle, when it is
  /// \f$m_i a\f$ on each (uniform gravity); empty for any other force (the default). A
  /// ParticleSystem adds \f$a\f$ to the free particles after dividing the other forces by the
  /// masses, instead of accumulating \f$m_i a\f$ and dividing it again: one pass less, and no
  /// \f$\infty \cdot 0\f$ to avoid for a pinned particle.
  virtual std::optional<Vec3> uniformAcceleration() const;
};

/// Uniform gravity \f$f^{(i)} = m_i\,g\f$ with potential \f$U = -\sum_i m_i\, g \cdot x_i\f$.
class UniformGravity final : public Force {
 public:
  /// \param g gravitational acceleration, world frame [m/s^2], e.g. (0, 0, -9.81)
  explicit UniformGravity(const Vec3& g);
  std::string name() const override { return "uniform gravity"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  bool addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const override;
  /// g: gravity accelerates every free particle alike.
  std::optional<Vec3> uniformAcceleration() const override { return g; }
  const Vec3 g;  ///< gravitational acceleration, world frame [m/s^2]
};

/// Newtonian gravity between every pair, softened by \f$\epsilon\f$:
/// \f$F_{ij} = G m_i m_j\,(x_j - x_i) / (|x_j - x_i|^2 + \epsilon^2)^{3/2}\f$ on \f$i\f$, with
/// \f$U = -\sum_{i<j} G m_i m_j / \sqrt{|x_j - x_i|^2 + \epsilon^2}\f$.
class NBodyGravity final : public Force {
 public:
  /// \param G gravitational constant [m^3 kg^-1 s^-2], positive
  /// \param softening \f$\epsilon \ge 0\f$ [m]; keeps close encounters finite
  NBodyGravity(double G, double softening);
  std::string name() const override { return "N-body gravity"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  const double G;          ///< gravitational constant [m^3 kg^-1 s^-2]
  const double softening;  ///< softening length epsilon [m]
};

/// Viscous drag \f$f^{(i)} = -d\,v_i\f$ (dissipative: no potential).
class ViscousDrag final : public Force {
 public:
  /// \param d drag coefficient [kg/s], non-negative
  explicit ViscousDrag(double d);
  std::string name() const override { return "viscous drag"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  bool addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const override;
  const double d;  ///< drag coefficient [kg/s]
};

/// The damped spring of the lecture between particles \f$a\f$ and \f$b\f$: with
/// \f$l = x_a - x_b\f$, \f$\dot l = v_a - v_b\f$ and rest length \f$r\f$,
/// \f[ f_a = -\Big[k_s(|l| - r) + k_d \frac{\dot l \cdot l}{|l|}\Big] \frac{l}{|l|}, \qquad f_b = -f_a, \f]
/// with potential \f$U = \frac12 k_s (|l| - r)^2\f$ (the damping part is dissipative).
class DampedSpring final : public Force {
 public:
  /// \param a,b particle indices, distinct
  /// \param rest rest length \f$r \ge 0\f$ [m]
  /// \param ks stiffness \f$k_s \ge 0\f$ [N/m]
  /// \param kd damping \f$k_d \ge 0\f$ [N s/m]
  DampedSpring(Index a, Index b, double rest, double ks, double kd);
  std::string name() const override { return "damped spring"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  /// Analytic Jacobians: with \f$u = l/|l|\f$ and \f$s = k_s(|l|-r) + k_d\,\dot l \cdot u\f$,
  /// \f$\partial f_a/\partial l = -\big[k_s u u^T + \frac{k_d}{|l|} u \dot l^T (\mathbb 1 - u u^T)
  /// + \frac{s}{|l|}(\mathbb 1 - u u^T)\big]\f$ and \f$\partial f_a/\partial \dot l = -k_d u u^T\f$.
  bool addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const override;
  const Index a;      ///< first particle
  const Index b;      ///< second particle
  const double rest;  ///< rest length r [m]
  const double ks;    ///< stiffness [N/m]
  const double kd;    ///< damping [N s/m]
};

/// Lennard-Jones between every pair: \f$U = \sum_{i<j} 4\varepsilon[(\sigma/r)^{12} - (\sigma/r)^6]\f$,
/// \f$r = |x_i - x_j|\f$; the force on \f$i\f$ is
/// \f$\frac{24\varepsilon}{r}\,[2(\sigma/r)^{12} - (\sigma/r)^6]\,\frac{x_i - x_j}{r}\f$.
class LennardJones final : public Force {
 public:
  /// \param epsilon well depth \f$\varepsilon > 0\f$ [J]
  /// \param sigma distance where the potential crosses zero, \f$\sigma > 0\f$ [m]
  LennardJones(double epsilon, double sigma);
  std::string name() const override { return "Lennard-Jones"; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  const double epsilon;  ///< well depth [J]
  const double sigma;    ///< zero-crossing distance [m]
};

/// A set of particles with masses and the forces acting on them.
class ParticleSystem final : public System {
 public:
  /// \param masses one mass per particle [kg], each positive; +infinity pins a particle (it
  ///        feels no acceleration). Throws InvalidInput naming the first bad mass.
  explicit ParticleSystem(VecX masses);

  /// Adds a force; throws InvalidInput if a spring names a particle that does not exist.
  void addForce(std::shared_ptr<const Force> force);

  Index count() const { return masses_.size(); }                  ///< number of particles n
  const VecX& masses() const { return masses_; }                   ///< masses [kg], length n
  /// Inverse masses \f$1/m_i\f$ [1/kg], length n; 0 for a pinned particle.
  const VecX& inverseMasses() const { return inverse_masses_; }
  /// The forces, in the order they were added.
  const std::vector<std::shared_ptr<const Force>>& forces() const { return forces_; }
  /// The forces the derivative accumulates: forces() less those with a uniformAcceleration().
  const std::vector<const Force*>& accumulatedForces() const { return accumulated_forces_; }
  /// The sum of the forces' uniform accelerations (uniform gravity), world frame [m/s^2]: what
  /// every free particle gets on top of its accumulated force divided by its mass.
  const Vec3& uniformAcceleration() const { return uniform_acceleration_; }
  Index positionSize() const override { return 3 * count(); }
  Index velocitySize() const override { return 3 * count(); }
  std::string name() const override { return "particle system"; }
  /// True: \f$\dot x = v\f$, so a drift reads the velocities in place (positionRateView()).
  bool positionRateIsVelocity() const override { return true; }

  /// Builds a state from positions and velocities (each 3 x n); throws InvalidInput on a size
  /// mismatch or a non-finite entry.
  VecX makeState(const Mat3X& x, const Mat3X& v) const;
  /// The view forces see of state `X`.
  ParticleView view(const VecX& X) const;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;
  bool computeJacobian(const VecX& X, MatX& J) const override;

 private:
  template <int>
  friend struct remote::Access;  // the grader calls the derivative remotely
  VecX masses_;
  VecX inverse_masses_;
  std::vector<std::shared_ptr<const Force>> forces_;
  std::vector<const Force*> accumulated_forces_;
  Vec3 uniform_acceleration_ = Vec3::Zero();
};

/// \name Diagnostics (student functions, Lab 1 section 4)
///@{

/// Kinetic energy \f$T = \sum_i \frac12 m_i |v_i|^2\f$ [J]; pinned particles contribute 0.
double kineticEnergy(const ParticleSystem& sys, const VecX& X);
/// Potential energy: the sum of every force's potential() [J].
double potentialEnergy(const ParticleSystem& sys, const VecX& X);
/// Linear momentum \f$P = \sum_i m_i v_i\f$ [kg m/s]; pinned particles are left out.
Vec3 linearMomentum(const ParticleSystem& sys, const VecX& X);
/// Angular momentum about the origin \f$L = \sum_i x_i \times m_i v_i\f$ [kg m^2/s]; pinned
/// particles are left out.
Vec3 angularMomentum(const ParticleSystem& sys, const VecX& X);
///@}

}  // namespace physlab
