#include "physlab/integrators.hpp"

#include "physlab/error.hpp"

namespace physlab {

Integrator::Integrator(Method method, NewtonSettings newton) : method_(method), newton_(newton) {
  if (newton_.max_iterations < 1) throw InvalidInput("Newton max_iterations must be at least 1");
  requirePositive(newton_.tolerance, "Newton tolerance");
}

void Integrator::step(const System& sys, VecX& X, double h) {
  requirePositive(h, "step size h");
  sys.validateState(X);
  const Index n = sys.size();
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
  // Finite input that came out non-finite: the method diverged (explicit Euler past its
  // stability limit, say), which is not the caller's bad input
  if (!X.allFinite()) {
    throw NumericalFailure(methodName(method_) + " diverged: the state became non-finite with h = " +
                           std::to_string(h) + " (a smaller step or a stable method may help)");
  }
}

}  // namespace physlab
