/// \file integrators.hpp
/// \brief Lab 1: one-step ODE integrators on any System.
///
/// Each method advances a state \f$X_n\f$ by one step of size \f$h\f$ to \f$X_{n+1}\f$ in place.
/// Notation follows the lecture: \f$X = [q;\ p]\f$, \f$f(X) = [\dot q;\ \dot p]\f$. The student
/// implements the seven free functions below (labs/01_particles/integrators.cpp); the Integrator
/// class around them validates input, sizes the workspace and projects the state afterwards.
#pragma once

#include <array>
#include <string>

#include "physlab/dense_lu.hpp"
#include "physlab/math.hpp"
#include "physlab/system.hpp"

namespace physlab {

/// The integrators of Lab 1, in the order the handout introduces them.
enum class Method {
  ExplicitEuler,    ///< \f$X_{n+1} = X_n + h f(X_n)\f$; order 1, 1 evaluation
  SymplecticEuler,  ///< \f$p_{n+1} = p_n + h \dot p(q_n,p_n)\f$, then \f$q_{n+1} = q_n + h \dot q(q_n,p_{n+1})\f$; order 1, 1 evaluation (the drift reads \f$\dot q\f$, which is none)
  Midpoint,         ///< half Euler step, then a full step with the midpoint slope; order 2, 2 evaluations
  Trapezoid,        ///< Heun: average of the slopes at both ends of an Euler step; order 2, 2 evaluations
  RK4,              ///< classical Runge-Kutta; order 4, 4 evaluations
  Verlet,           ///< velocity Verlet (kick-drift-kick); order 2 for position-only forces, 2 evaluations
  ImplicitEuler,    ///< \f$X_{n+1} = X_n + h f(X_{n+1})\f$ by Newton's method; order 1
};

/// Every method, for loops over all of them.
inline constexpr std::array<Method, 7> kAllMethods = {
    Method::ExplicitEuler, Method::SymplecticEuler, Method::Midpoint, Method::Trapezoid,
    Method::RK4,           Method::Verlet,          Method::ImplicitEuler};

/// Display name of a method ("explicit Euler", "RK4", ...).
std::string methodName(Method method);
/// Short identifier of a method, safe in file names and command lines ("explicit_euler", "rk4").
std::string methodId(Method method);
/// The method whose methodId() is `id`; throws InvalidInput naming the unknown id.
Method methodFromId(const std::string& id);
/// Global order of accuracy of a method (error of a fixed-time run is \f$O(h^{order})\f$).
int methodOrder(Method method);
/// Spectral radius (largest \f$|\lambda|\f$) of a real 2 x 2 matrix, such as one step of a method
/// on the harmonic oscillator: from \f$\lambda^2 - \operatorname{tr}A\,\lambda + \det A = 0\f$
/// in closed form (Eigen's general eigensolver costs seconds of compile time in every file).
double spectralRadius(const Eigen::Matrix2d& A);

/// Scratch vectors a step may use, so that a step allocates nothing. Each has length size()
/// of the system when a step starts: `k1`..`k4` for slopes, `X_tmp` for intermediate states.
struct Workspace {
  VecX k1;     ///< slope (length of the state)
  VecX k2;     ///< slope (length of the state)
  VecX k3;     ///< slope (length of the state)
  VecX k4;     ///< slope (length of the state)
  VecX X_tmp;  ///< intermediate state (length of the state)
};

/// Settings of the Newton iteration inside implicit Euler.
struct NewtonSettings {
  int max_iterations = 25;  ///< give up (NumericalFailure) after this many iterations
  double tolerance = 1e-12; ///< stop when \f$\|\Delta X\| \le\f$ tolerance \f$(1 + \|X\|)\f$
};

/// \name Student functions: one step of size h, in place on X.
/// `X` has length sys.size() and finite entries, `h > 0`, and every vector in `ws` has length
/// sys.size(); the Integrator class guarantees all three.
///@{

/// \f$X_{n+1} = X_n + h f(X_n)\f$. Handout: Lab 1, section 3.1.
void explicitEuler(const System& sys, double h, VecX& X, Workspace& ws);
/// \f$p_{n+1} = p_n + h\,\dot p(q_n, p_n)\f$; \f$q_{n+1} = q_n + h\,\dot q(q_n, p_{n+1})\f$, the
/// drift reading \f$\dot q\f$ through sys.positionRateView() (no copy for particles).
/// Handout: Lab 1, section 3.2.
void symplecticEuler(const System& sys, double h, VecX& X, Workspace& ws);
/// \f$X_m = X_n + \frac h2 f(X_n)\f$; \f$X_{n+1} = X_n + h f(X_m)\f$. Handout: Lab 1, section 3.3.
void midpoint(const System& sys, double h, VecX& X, Workspace& ws);
/// \f$\tilde X = X_n + h f(X_n)\f$; \f$X_{n+1} = X_n + \frac h2 (f(X_n) + f(\tilde X))\f$.
/// Handout: Lab 1, section 3.3.
void trapezoid(const System& sys, double h, VecX& X, Workspace& ws);
/// \f$k_1 = f(X_n)\f$, \f$k_2 = f(X_n + \frac h2 k_1)\f$, \f$k_3 = f(X_n + \frac h2 k_2)\f$,
/// \f$k_4 = f(X_n + h k_3)\f$; \f$X_{n+1} = X_n + \frac h6(k_1 + 2k_2 + 2k_3 + k_4)\f$.
/// Handout: Lab 1, section 3.4.
void rk4(const System& sys, double h, VecX& X, Workspace& ws);
/// Velocity Verlet: \f$p_{n+1/2} = p_n + \frac h2 \dot p(q_n,p_n)\f$;
/// \f$q_{n+1} = q_n + h\,\dot q(q_n, p_{n+1/2})\f$;
/// \f$p_{n+1} = p_{n+1/2} + \frac h2 \dot p(q_{n+1}, p_{n+1/2})\f$; the drift reads \f$\dot q\f$
/// through sys.positionRateView(). Handout: Lab 1, section 3.5.
void verlet(const System& sys, double h, VecX& X, Workspace& ws);
/// Solve \f$G(X_{n+1}) = X_{n+1} - X_n - h f(X_{n+1}) = 0\f$ by Newton's method,
/// \f$(\mathbb 1 - h\,\partial f/\partial X)\,\Delta X = -G\f$, with sys.jacobian(). Throws
/// NumericalFailure when `newton.max_iterations` pass without convergence.
/// Handout: Lab 1, section 3.6.
void implicitEuler(const System& sys, double h, VecX& X, Workspace& ws,
                   const NewtonSettings& newton);
///@}

/// Advances states of a System with one chosen Method, reusing its workspace between steps.
///
/// \code
///   Integrator rk(Method::RK4);
///   for (int n = 0; n < steps; ++n) rk.step(system, X, h);
/// \endcode
class Integrator {
 public:
  /// \param method the method every step() uses
  /// \param newton Newton settings, used by Method::ImplicitEuler only
  explicit Integrator(Method method, NewtonSettings newton = {});

  /// One step of size `h` on `X` in place; afterwards calls sys.project(X). Throws InvalidInput
  /// if `h` is not positive and finite or `X` has the wrong size, and NumericalFailure naming the
  /// entry if `X` is not finite after the step: one check of the result per step, which also
  /// catches a non-finite entry passed in (every method adds an increment to X, and a non-finite
  /// entry stays non-finite), without telling it apart from a divergence. Implicit Euler checks
  /// its input before Newton's method too (InvalidInput).
  void step(const System& sys, VecX& X, double h);

  /// The method this integrator uses.
  Method method() const { return method_; }

 private:
  Method method_;
  NewtonSettings newton_;
  Workspace ws_;
};

}  // namespace physlab
