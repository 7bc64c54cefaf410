/// \file system.hpp
/// \brief The small interface every integrator works on: a second-order system in first-order form.
///
/// A system's state is one flat vector \f$X = [q;\ p]\f$: first the position-like part \f$q\f$
/// (length positionSize()), then the velocity-like part \f$p\f$ (length velocitySize()). For
/// particles \f$q = [x_1 \dots x_n]\f$ and \f$p = [v_1 \dots v_n]\f$; for a rigid body (Lab 3)
/// \f$q = [x, q]\f$ and \f$p = [P, L]\f$. The ODE is
/// \f[ \frac{dX}{dt} = f(X) = \begin{bmatrix} \dot q(q, p) \\ \dot p(q, p) \end{bmatrix}. \f]
/// Splitting the state lets symplectic Euler and Verlet update \f$p\f$ and \f$q\f$ in turn.
///
/// The system is the constant *description* (masses, forces, parameters); the state lives
/// outside it and is passed in, so one system can advance many states.
#pragma once

#include <string>
#include <string_view>

#include "physlab/math.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// A second-order ODE system \f$\dot X = f(X)\f$ with state \f$X = [q;\ p]\f$.
///
/// Public calls validate their arguments and count evaluations; derived classes implement the
/// protected `compute*` hooks (the non-virtual interface idiom).
class System {
 public:
  virtual ~System() = default;

  /// Length of the position-like part \f$q\f$.
  virtual Index positionSize() const = 0;
  /// Length of the velocity-like part \f$p\f$.
  virtual Index velocitySize() const = 0;
  /// Length of the whole state, positionSize() + velocitySize().
  Index size() const { return positionSize() + velocitySize(); }
  /// A short human-readable name used in reports and charts.
  virtual std::string name() const = 0;

  /// \f$\dot q(q, p)\f$ into `qdot` (length positionSize()).
  void positionRate(const VecX& X, Eigen::Ref<VecX> qdot) const;
  /// \f$\dot q(q, p)\f$ to read, without a copy where the system allows one: a view of `X`'s own
  /// velocity part \f$p\f$ when positionRateIsVelocity(), otherwise positionRate() written into
  /// `scratch` (length positionSize()) and a view of it. The view is valid until `X` or `scratch`
  /// changes; `q += h * positionRateView(X, scratch)` is a drift.
  Eigen::Map<const VecX> positionRateView(const VecX& X, Eigen::Ref<VecX> scratch) const;
  /// Whether \f$\dot q = p\f$ exactly (particles: \f$\dot x = v\f$), so that positionRateView()
  /// can hand out \f$p\f$ itself. False by default (a rigid body's \f$\dot q\f$ is not its
  /// \f$p = [P, L]\f$).
  virtual bool positionRateIsVelocity() const { return false; }
  /// \f$\dot p(q, p)\f$ into `pdot` (length velocitySize()); counts one force evaluation.
  void velocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const;
  /// The whole derivative \f$f(X) = [\dot q;\ \dot p]\f$ into `dXdt` (length size());
  /// counts one force evaluation.
  void derivative(const VecX& X, VecX& dXdt) const;
  /// The Jacobian \f$\partial f / \partial X\f$ (size() x size()): analytic where the system
  /// provides one, central finite differences otherwise (costing 2 size() evaluations).
  MatX jacobian(const VecX& X) const;
  /// Pulls a state back onto its constraint manifold after a step (e.g. renormalises a
  /// quaternion). The default does nothing.
  virtual void project(VecX& X) const;

  /// Throws InvalidInput unless `X` has length size() and finite entries.
  void validateState(const VecX& X, std::string_view what = "state") const;

  /// Number of force evaluations (calls of velocityRate or derivative) since construction or
  /// the last resetCount(); the cost axis of the work-precision charts.
  long forceEvaluations() const { return force_evaluations_; }
  /// Sets forceEvaluations() back to zero.
  void resetCount() const { force_evaluations_ = 0; }

 protected:
  /// Implement \f$\dot q\f$; `X` has been validated only for size.
  virtual void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const = 0;
  /// Implement \f$\dot p\f$.
  virtual void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const = 0;
  /// Fill `J` (already sized size() x size(), zeroed) with \f$\partial f / \partial X\f$ and
  /// return true, or return false to fall back on finite differences (the default).
  virtual bool computeJacobian(const VecX& X, MatX& J) const;

 private:
  template <int>
  friend struct remote::Access;  // a system evaluated by a grading worker counts its evaluations here
  mutable long force_evaluations_ = 0;
};

}  // namespace physlab
