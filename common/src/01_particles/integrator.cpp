#include "physlab/integrators.hpp"

#include "physlab/error.hpp"

namespace physlab {

Integrator::Integrator(Method method, NewtonSettings newton) : method_(method), newton_(newton) {
  if (newton_.max_iterations < 1) throw InvalidInput("Newton max_iterations must be at least 1");
  requirePositive(newton_.tolerance, "Newton tolerance");
}

void Integrator::step(const System& sys, VecX& X, double h) {
  requirePositive(h, "step size h");
  const Index n = sys.size();
  if (X.size() != n) requireSize(X.size(), n, sys.name() + " state");
  // Newton's method would report a non-finite input as non-convergence; its Jacobian costs far
  // more than this pass, so implicit Euler checks its input first.
  if (method_ == Method::ImplicitEuler) sys.validateState(X);
  for (VecX* v : {&ws_.k1, &ws_.k2, &ws_.k3, &ws_.k4, &ws_.X_tmp}) v->resize(n);
  switch (method_) {
    case Method::ExplicitEuler: explicitEuler(sys, h, X, ws_); break;
    case Method::SymplecticEuler: symplecticEuler(sys, h, X, ws_); break;
    case Method::Midpoint: midpoint(sys, h, X, ws_); break;
    case Method::Trapezoid: trapezoid(sys, h, X, ws_); break;
    case Method::RK4: rk4(sys, h, X, ws_); break;
    case Method::Verlet: verlet(sys, h, X, ws_); break;
    case Method::ImplicitEuler: implicitEuler(sys, h, X, ws_, newton_); break;
  }
  sys.project(X);
  // One finiteness check per step, of the result only. Every method adds an increment to X, so a
  // non-finite entry passed in stays non-finite (inf + finite = inf, NaN + anything = NaN) and is
  // caught here too, at the cost of not telling it apart from a divergence: the message names both.
  if (const Index bad = firstNonFinite(X); bad >= 0) {
    throw NumericalFailure(methodName(method_) + " step with h = " + std::to_string(h) + " on the " + sys.name() +
                           " left a non-finite entry at " + std::to_string(bad) +
                           ": the state passed in had one, or the method diverged (a smaller step or a "
                           "stable method may help)");
  }
}

}  // namespace physlab
