// Lab 1, section 3: one-step integrators. Each works on any System through its small interface.
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "physlab/error.hpp"
#include "physlab/integrators.hpp"

namespace physlab {

void explicitEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  // Evaluate the slope at the start of the step
  // TODO(student): sys.derivative(X, ws.k1) fills ws.k1 with f(X).
  // Follow it for the whole step
  // TODO(student): X += h * f(X_n).
  notImplemented("explicitEuler", "Lab 1 handout, section 3.1", sys, h, X, ws);
}

void symplecticEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  // Kick: update the velocities with the forces at the old positions
  // TODO(student): sys.velocityRate(X, ws.k1.head(np)), then update X.tail(np) (np = sys.velocitySize()).
  // Drift: move the positions with the new velocities
  // TODO(student): X.head(nq) += h qdot, qdot from sys.positionRateView(X, ws.k2.head(nq)) (it now sees the new velocities).
  notImplemented("symplecticEuler", "Lab 1 handout, section 3.2", sys, h, X, ws);
}

void midpoint(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take half an Euler step to the midpoint
  // TODO(student): ws.X_tmp = X_n + h/2 f(X_n).
  // Take the full step with the slope at the midpoint
  // TODO(student): X_{n+1} = X_n + h f(X_tmp).
  notImplemented("midpoint", "Lab 1 handout, section 3.3", sys, h, X, ws);
}

void trapezoid(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take a full Euler step to predict the end of the step
  // TODO(student): keep f(X_n) in ws.k1; predict ws.X_tmp = X_n + h f(X_n).
  // Average the slopes at both ends
  // TODO(student): X_{n+1} = X_n + h/2 (f(X_n) + f(X_tmp)).
  notImplemented("trapezoid", "Lab 1 handout, section 3.3", sys, h, X, ws);
}

void rk4(const System& sys, double h, VecX& X, Workspace& ws) {
  // Sample the slope at the start, twice at the middle, and at the end
  // TODO(student): k1..k4 as in the handout; reuse ws.X_tmp for each trial state.
  // Combine them with weights 1/6, 2/6, 2/6, 1/6
  // TODO(student): X += h/6 (k1 + 2 k2 + 2 k3 + k4).
  notImplemented("rk4", "Lab 1 handout, section 3.4", sys, h, X, ws);
}

void verlet(const System& sys, double h, VecX& X, Workspace& ws) {
  // Kick the velocities by half a step
  // TODO(student): p += h/2 pdot(q_n, p_n).
  // Drift the positions by a full step with the half-step velocities
  // TODO(student): q += h qdot(q_n, p_{n+1/2}), qdot from sys.positionRateView(X, ws.k2.head(nq)).
  // Kick the velocities by the second half step with the forces at the new positions
  // TODO(student): p += h/2 pdot(q_{n+1}, p_{n+1/2}).
  notImplemented("verlet", "Lab 1 handout, section 3.5", sys, h, X, ws);
}

void implicitEuler(const System& sys, double h, VecX& X, Workspace& ws,
                   const NewtonSettings& newton) {
  // Start Newton's method from an explicit Euler prediction of the end of the step
  // TODO(student): keep X_n (ws.X_tmp = X), then X = X_n + h f(X_n) as the first guess.
  // TODO(student): loop at most newton.max_iterations times over the three chunks below.
    // Form the residual G(X) = X - X_n - h f(X)
    // TODO(student): sys.derivative(X, ws.k1); ws.k2 = X - X_n - h ws.k1.
    // Solve (1 - h df/dX) dX = -G for the Newton update
    // TODO(student): A = I - h sys.jacobian(X); A.partialPivLu().solve(-G); add the update to X.
    // Stop when the update is negligible next to the state
    // TODO(student): return once |dX| <= newton.tolerance (1 + |X|); after the loop throw NumericalFailure.
  notImplemented("implicitEuler", "Lab 1 handout, section 3.6", sys, h, X, ws, newton);
}

}  // namespace physlab
