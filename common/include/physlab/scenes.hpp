/// \file scenes.hpp
/// \brief Reference systems with known answers, shared by tests, demos and benchmarks.
///
/// These are framework code, not student code: they give the integrator tests an oracle that
/// does not depend on the student's forces.
#pragma once

#include <string>

#include "physlab/system.hpp"

namespace physlab {

/// The harmonic oscillator \f$\ddot x = -\omega^2 x\f$ (unit mass), state \f$X = [x;\ v]\f$.
/// Exact solution \f$x(t) = x_0\cos\omega t + (v_0/\omega)\sin\omega t\f$.
class HarmonicOscillator final : public System {
 public:
  /// \param omega angular frequency \f$\omega > 0\f$ [rad/s]
  explicit HarmonicOscillator(double omega);
  Index positionSize() const override { return 1; }
  Index velocitySize() const override { return 1; }
  std::string name() const override { return "harmonic oscillator"; }
  /// \f$E = \frac12(v^2 + \omega^2 x^2)\f$ [J per kg]
  double energy(const VecX& X) const;
  /// The exact state at time `t` from `X0`.
  VecX exact(const VecX& X0, double t) const;
  const double omega;  ///< angular frequency [rad/s]

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;
  bool computeJacobian(const VecX& X, MatX& J) const override;
};

/// A planet around a fixed sun, \f$\ddot r = -\mu\, r / |r|^3\f$, state \f$X = [r;\ v]\f$ in 3D.
/// Energy \f$H = \frac12 |v|^2 - \mu/|r|\f$ per unit mass.
class Kepler final : public System {
 public:
  /// \param mu gravitational parameter \f$\mu = GM > 0\f$ [m^3/s^2]
  explicit Kepler(double mu);
  Index positionSize() const override { return 3; }
  Index velocitySize() const override { return 3; }
  std::string name() const override { return "Kepler orbit"; }
  /// \f$H = \frac12 |v|^2 - \mu/|r|\f$ [J per kg]
  double energy(const VecX& X) const;
  /// The state at perihelion of an orbit with semi-major axis `a` and eccentricity `e`
  /// (\f$0 \le e < 1\f$): \f$r = (a(1-e), 0, 0)\f$, \f$v = (0, \sqrt{\mu(1+e)/(a(1-e))}, 0)\f$.
  VecX perihelionState(double a, double e) const;
  /// Orbital period \f$2\pi\sqrt{a^3/\mu}\f$ [s] of an orbit with semi-major axis `a`.
  double period(double a) const;
  const double mu;  ///< gravitational parameter [m^3/s^2]

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;
};

}  // namespace physlab
